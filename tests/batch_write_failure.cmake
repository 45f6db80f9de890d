# A job whose output fails only when it is written (its PNG preview path is a
# folder) is reported against its own line while the jobs around it, traced
# and written in overlap with it, finish; the exit code is 2.
# -DSPECTRACE=... -DSOURCE_DIR=... -DOUT=... -DDEVICE=gpu|cpu
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT}/blocked.png)
execute_process(COMMAND ${SPECTRACE} batch ${SOURCE_DIR}/tests/data/batch/write_failure.jsonl --out-dir ${OUT}
  --device ${DEVICE} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "exit code ${rc}, expected 2\n${out}\n${err}")
endif()
if(NOT err MATCHES "write_failure.jsonl:5: /output: [^\n]*blocked.png")
  message(FATAL_ERROR "the write failure is not reported against write_failure.jsonl:5:\n${err}")
endif()
foreach(row "write_failure.jsonl:4 [^\n]* ok" "write_failure.jsonl:5 [^\n]* FAILED" "write_failure.jsonl:6 [^\n]* ok"
        "3 jobs: 2 rendered, 0 skipped, 1 failed")
  if(NOT out MATCHES "${row}")
    message(FATAL_ERROR "no summary row matching '${row}' in:\n${out}")
  endif()
endforeach()
foreach(file first.exr first.png last.exr last.png)
  if(NOT EXISTS ${OUT}/${file})
    message(FATAL_ERROR "${file} is missing:\n${err}")
  endif()
endforeach()
# The EXR, which marks a job complete for --skip-existing, is written last.
if(EXISTS ${OUT}/blocked.exr)
  message(FATAL_ERROR "blocked.exr was written though its job failed")
endif()
