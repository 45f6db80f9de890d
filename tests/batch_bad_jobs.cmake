# A batch with bad jobs: the good ones finish, each bad one is reported with
# the job file, line and field, and the exit code is 2. --fail-fast stops at
# the first failure. -DSPECTRACE=... -DSOURCE_DIR=... -DOUT=...
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${OUT})
set(jobs ${SOURCE_DIR}/tests/data/batch/bad.jsonl)
execute_process(COMMAND ${SPECTRACE} batch ${jobs} --out-dir ${OUT}/keep --device cpu -q --no-png
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "exit code ${rc}, expected 2\n${out}\n${err}")
endif()
foreach(good good1 good2)
  if(NOT EXISTS ${OUT}/keep/${good}.exr)
    message(FATAL_ERROR "the good job's ${good}.exr is missing\n${err}")
  endif()
endforeach()
set(expected
  "bad.jsonl:2: /set/~1lights~13~1power_w: unknown pointer /lights/3/power_w"
  "bad.jsonl:3: /scene [^\n]*lamp.json: /lights/0/power_w: must be"
  "bad.jsonl:4: /scene [^\n]*lamp.json: /lights/0/spd/csv: SPD file not found"
  "bad.jsonl:5: /output: cannot create the folder"
  "bad.jsonl:6: /beam: unknown key \"beam\" in a job; did you mean \"beams\"")
foreach(regex IN LISTS expected)
  if(NOT err MATCHES "${regex}")
    message(FATAL_ERROR "no error matching '${regex}' in:\n${err}")
  endif()
endforeach()
foreach(made unknown negative csv typo)
  if(EXISTS ${OUT}/keep/${made}.exr)
    message(FATAL_ERROR "the bad job's ${made}.exr was written")
  endif()
endforeach()

execute_process(COMMAND ${SPECTRACE} batch ${jobs} --out-dir ${OUT}/fast --device cpu -q --no-png --fail-fast
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT EXISTS ${OUT}/fast/good1.exr OR EXISTS ${OUT}/fast/good2.exr OR err MATCHES "bad.jsonl:3")
  message(FATAL_ERROR "--fail-fast: exit code ${rc}; it must stop after the first bad job\n${err}")
endif()
