# SIGINT during a long render of the prism (-DDEVICE=cpu or gpu, -DWAIT:
# seconds before the signal): the render must stop within 2 s of it, exit
# 130 and write the image of the beams it finished. Its log (stderr to a
# file) must hold no carriage return; with WAIT past 10 s it holds a plain
# progress line with rate and ETA, and the checkpoint notices on lines of
# their own. Batches were 4M beams, so a prism on lavapipe took up to 20 s
# to answer, and the log was one line glued with '\r'.
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")

execute_process(COMMAND sh -c [=[
    "$1" render "$2" --device "$3" --beams 1e15 --checkpoint-seconds 4 -o "$4/prism.exr" --no-png 2>"$4/log" &
    pid=$!
    sleep "$5"
    sent=$(date +%s%N)
    kill -INT $pid
    wait $pid
    rc=$?
    echo "rc=$rc ms=$(( ($(date +%s%N) - sent) / 1000000 ))"
  ]=] sh "${SPECTRACE}" "${SCENE}" "${DEVICE}" "${DIR}" "${WAIT}"
  OUTPUT_VARIABLE out TIMEOUT 120)
file(READ "${DIR}/log" log)
if(NOT out MATCHES "rc=([0-9]+) ms=([0-9]+)")
  message(FATAL_ERROR "no exit code: ${out}\n${log}")
endif()
set(rc ${CMAKE_MATCH_1})
set(ms ${CMAKE_MATCH_2})
message(STATUS "exit ${rc}, ${ms} ms after SIGINT")
if(NOT rc EQUAL 130)
  message(FATAL_ERROR "exit code ${rc}, not 130:\n${log}")
endif()
if(ms GREATER 2000)
  message(FATAL_ERROR "the render took ${ms} ms to stop after SIGINT (at most 2000):\n${log}")
endif()
if(NOT EXISTS "${DIR}/prism.exr" OR NOT log MATCHES "interrupted after [0-9]+ of 1000000000000000 beams; the image holds")
  message(FATAL_ERROR "no image of the finished beams:\n${log}")
endif()
string(FIND "${log}" "\r" cr)
if(NOT cr EQUAL -1)
  message(FATAL_ERROR "the log holds a carriage return:\n${log}")
endif()
if(WAIT GREATER 10)
  if(NOT log MATCHES "\nspectrace: +[0-9.]+%, [0-9]+ of 1000000000000000 beams, [0-9.e+-]+ Mbeam/s, 0:1[0-9] elapsed, ETA [0-9d :]+\n")
    message(FATAL_ERROR "no progress line with rate, elapsed time and ETA:\n${log}")
  endif()
  if(NOT log MATCHES "\nspectrace: checkpoint: [0-9]+ beams -> [^\n]*prism.exr\n")
    message(FATAL_ERROR "no checkpoint notice on a line of its own:\n${log}")
  endif()
endif()
