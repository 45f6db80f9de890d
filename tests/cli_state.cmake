# cmake -DSPECTRACE=... -DCOMPARE=... -DSCENE=... -DDIR=... -DMODE=shards|kill -P cli_state.cmake
# shards: three shards of one render, traced on gpu, cpu and gpu, merged on
#   the gpu, give the same EXR pixels as one gpu render of all the beams.
# kill: a render killed (SIGKILL, by the timeout) after its first checkpoints
#   resumes from its state (removing the stale temporary files of the killed
#   process) and ends with the same EXR pixels as an uninterrupted render.
file(REMOVE_RECURSE ${DIR})
file(MAKE_DIRECTORY ${DIR})
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)

if(MODE STREQUAL "shards")
  set(beams 1200000)
  set(devices gpu cpu gpu)
  foreach(i 0 1 2)
    list(GET devices ${i} device)
    run(${SPECTRACE} render ${SCENE} --beams ${beams} --shard ${i}/3 --device ${device}
        -o ${DIR}/shard${i}.exr --state ${DIR}/shard${i}.state -q --no-png)
  endforeach()
  run(${SPECTRACE} merge ${DIR}/shard0.state ${DIR}/shard1.state ${DIR}/shard2.state -o ${DIR}/merged.exr
      --device gpu --state ${DIR}/merged.state -q --no-png)
  run(${SPECTRACE} render ${SCENE} --beams ${beams} --device gpu -o ${DIR}/whole.exr -q --no-png)
  expect_same(${DIR}/merged.exr ${DIR}/whole.exr)
  # The merged state merges no further with any of its parts.
  execute_process(COMMAND ${SPECTRACE} merge ${DIR}/merged.state ${DIR}/shard1.state -o ${DIR}/again.exr -q
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "overlap")
    message(FATAL_ERROR "an overlapping merge was not refused with exit code 2 (${rc}): ${err}")
  endif()
  # merge -o goes through render's output checks: an input state, a device
  # node and a .png are refused (exit 2) and the state is left as it was.
  file(SHA256 ${DIR}/shard0.state before)
  foreach(output ${DIR}/shard0.state /dev/null ${DIR}/merged.png)
    execute_process(COMMAND ${SPECTRACE} merge ${DIR}/shard0.state ${DIR}/shard1.state -o ${output} -q
                    RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 2 OR NOT err MATCHES "spectrace: error: output ")
      message(FATAL_ERROR "merge -o ${output} was not refused with exit code 2 (${rc}): ${err}")
    endif()
  endforeach()
  file(SHA256 ${DIR}/shard0.state after)
  if(NOT before STREQUAL after)
    message(FATAL_ERROR "merge -o overwrote its input state")
  endif()
elseif(MODE STREQUAL "kill")
  # Enough beams that the first checkpoint (after 1 s) comes well before the
  # end; the kill waits for it, so more beams only lengthen the resumed and
  # the whole render. 5 million took about 1.0 s on one thread of an AMD
  # EPYC, so the checkpoint and the render's end raced; 20 million leave
  # about 3 s after it.
  set(beams 20000000)
  # SIGKILL once the first checkpoint's state exists (not after a fixed
  # time, which a loaded machine can spend before the first checkpoint);
  # exit 3 from the shell: the render ended by itself first.
  file(REMOVE ${DIR}/killed.state)
  execute_process(COMMAND sh -c "\"$0\" render \"$1\" --beams ${beams} --device cpu --threads 1 -o \"$2/killed.exr\" \
                                 --state \"$2/killed.state\" --checkpoint-seconds 1 -q --no-png & pid=$!; \
                                 while [ ! -e \"$2/killed.state\" ] && kill -0 $pid 2>/dev/null; do sleep 0.1; done; \
                                 kill -9 $pid 2>/dev/null || exit 3; wait $pid; exit 0"
                          ${SPECTRACE} ${SCENE} ${DIR}
                  TIMEOUT 120 RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the render was not killed after its first checkpoint (${rc}); raise the beam count")
  endif()
  if(NOT EXISTS ${DIR}/killed.state)
    message(FATAL_ERROR "no state was written before the kill")
  endif()
  # A temporary file the kill may have left (killed.exr.tmp-PID) stands in
  # for one for sure: the next render to that output removes it.
  file(WRITE ${DIR}/killed.exr.tmp-2147483000 "partial")
  run(${SPECTRACE} render ${SCENE} --beams ${beams} --device cpu --threads 1 -o ${DIR}/killed.exr
      --resume ${DIR}/killed.state --state ${DIR}/resumed.state -q --no-png)
  foreach(leftover killed.exr.tmp-2147483000 .killed.exr.lock)
    if(EXISTS ${DIR}/${leftover})
      message(FATAL_ERROR "${leftover} was left beside the output")
    endif()
  endforeach()
  file(RENAME ${DIR}/killed.exr ${DIR}/resumed.exr)
  run(${SPECTRACE} render ${SCENE} --beams ${beams} --device cpu --threads 1 -o ${DIR}/whole.exr -q --no-png)
  expect_same(${DIR}/resumed.exr ${DIR}/whole.exr)
else()
  message(FATAL_ERROR "unknown MODE ${MODE}")
endif()
