# Job files too big to plan are refused before anything renders, and a
# huge one that fits streams: its jobs are built one at a time, so SIGTERM
# stops it at once.
#   -DSPECTRACE=path  -DSCENE=scene.json  -DDIR=scratch folder
#   -DMODE=refused (the job count past 2^64 and past the limit)
#   -DMODE=interrupt (SIGTERM soon after the start of a sweep of 10^6 jobs)
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")

# A sweep line: `keys` (a list of JSON pointers), each with `count` values
# (all 1: a sweep's job count is the product of its value counts).
function(sweep_line out keys count)
  math(EXPR rest "${count} - 1")
  string(REPEAT "1, " ${rest} ones)
  set(sweep "")
  foreach(key IN LISTS keys)
    if(sweep)
      string(APPEND sweep ", ")
    endif()
    string(APPEND sweep "\"${key}\": [${ones}1]")
  endforeach()
  set(${out} "{\"scene\": \"${SCENE}\", \"output\": \"s{index}.exr\", \"beams\": 1, \"sweep\": {${sweep}}}\n" PARENT_SCOPE)
endfunction()

if(MODE STREQUAL "refused")
  # 256^8 = 2^64: a 64-bit count wraps to 0 (this ran "0 jobs" with exit 0).
  sweep_line(line "/lights/0/power_w;/lights/0/cone_deg;/lights/0/position/0;/lights/0/position/1;/lights/0/position/2;/camera/position/0;/camera/position/1;/render/seed" 256)
  file(WRITE "${DIR}/wraps.jsonl" "${line}")
  expect_refused(wraps "wraps.jsonl:1: /sweep: 2\\^64 or more combinations \\(256 x 256 x 256 x 256 x 256 x 256 x 256 x 256\\); a job file may hold at most 1000000 jobs"
                 "${SPECTRACE}" batch "${DIR}/wraps.jsonl" --device cpu -q --no-png)
  # One past the limit, after a line of one job: refused before any job is
  # built (this used to build all 10^6 scenes first).
  sweep_line(line "/lights/0/power_w;/render/seed" 1000)
  file(WRITE "${DIR}/past_limit.jsonl" "{\"scene\": \"${SCENE}\", \"output\": \"one.exr\"}\n${line}")
  expect_refused(past_limit "past_limit.jsonl:2: /sweep: 1000000 combinations \\(1000 x 1000\\) after 1 job on the lines above; a job file may hold at most 1000000 jobs"
                 "${SPECTRACE}" batch "${DIR}/past_limit.jsonl" --device cpu -q --no-png)
  file(GLOB written "${DIR}/*.exr")
  if(written)
    message(FATAL_ERROR "a refused job file rendered: ${written}")
  endif()
  message(STATUS "job files past 2^64 and past the limit were refused, nothing rendered")
elseif(MODE STREQUAL "interrupt")
  # At the limit: 10^6 jobs of one beam. SIGTERM two seconds in must end it
  # with exit 130 within seconds, whether it is reading the file or
  # rendering (this used to build every job first, deaf to SIGTERM).
  # timeout(1) passes SIGTERM on, and kills it after 60 s.
  sweep_line(line "/lights/0/power_w;/render/seed" 1000)
  file(WRITE "${DIR}/huge.jsonl" "${line}")
  execute_process(COMMAND sh -c [=[
      timeout -s KILL 60 "$1" batch "$2/huge.jsonl" --device cpu -q --no-png &
      pid=$!
      sleep 2
      sent=$(date +%s)
      kill -TERM $pid
      wait $pid
      echo "exit $? after $(( $(date +%s) - sent )) s"]=] sh "${SPECTRACE}" "${DIR}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT out MATCHES "exit ([0-9]+) after ([0-9]+) s")
    message(FATAL_ERROR "the run did not finish (${rc}):\n${out}${err}")
  endif()
  if(NOT CMAKE_MATCH_1 EQUAL 130 OR CMAKE_MATCH_2 GREATER 20)
    message(FATAL_ERROR "SIGTERM: exit ${CMAKE_MATCH_1} after ${CMAKE_MATCH_2} s, expected 130 within 20 s\n${err}")
  endif()
  message(STATUS "SIGTERM ended a batch of 10^6 jobs: ${out}")
else()
  message(FATAL_ERROR "MODE must be refused or interrupt")
endif()
