# --skip-existing renders only the jobs whose output is missing or holds
# fewer beams than the job asks for. -DSPECTRACE=... -DSOURCE_DIR=... -DOUT=...
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${OUT})
set(jobs ${SOURCE_DIR}/tests/data/batch/identical.jsonl)
function(batch expected)
  execute_process(COMMAND ${SPECTRACE} batch ${jobs} --out-dir ${OUT} --device cpu --no-png --skip-existing
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "${expected}")
    message(FATAL_ERROR "exit code ${rc}; expected '${expected}' in:\n${out}\n${err}")
  endif()
endfunction()
batch("5 jobs: 5 rendered, 0 skipped, 0 failed")
file(REMOVE ${OUT}/far.exr)
# An incomplete image (fewer beams than the job's) is rendered again.
execute_process(COMMAND ${SPECTRACE} render ${SOURCE_DIR}/scenes/reference/disk_off_axis.json -o ${OUT}/disk.exr
  --beams 1000 --seed 5 --device cpu -q --no-png RESULT_VARIABLE rc)
batch("5 jobs: 2 rendered, 3 skipped, 0 failed")
batch("5 jobs: 0 rendered, 5 skipped, 0 failed")
