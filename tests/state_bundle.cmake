# cmake -DSPECTRACE=... -DCOMPARE=... -DSCENE=... -DCSV=... -DDIR=... -P state_bundle.cmake
# A render state carries its scene and the files the scene names: two
# shards of a scene with a CSV spectrum, rendered with relative paths, have
# their states moved to another folder and the scene and the CSV deleted;
# `merge` there, reading no other file, gives the EXR pixels of one render of
# all the beams, and so does the merged state developed on its own.
file(REMOVE_RECURSE ${DIR})
file(MAKE_DIRECTORY ${DIR}/work/spd ${DIR}/elsewhere)
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)

# Runs a command in `folder`; fails the test with its output unless it exits 0.
function(run_in folder)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${folder} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err TIMEOUT 240)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}) in ${folder}: ${ARGN}\n${out}${err}")
  endif()
endfunction()

file(READ ${SCENE} text)
string(REPLACE "\"spd\": \"D65\"" "\"spd\": {\"csv\": \"spd/lamp.csv\"}" text "${text}")
if(NOT text MATCHES "lamp.csv")
  message(FATAL_ERROR "${SCENE} no longer has the \"spd\": \"D65\" this test replaces with a CSV spectrum")
endif()
file(WRITE ${DIR}/work/scene.json "${text}")
configure_file(${CSV} ${DIR}/work/spd/lamp.csv COPYONLY)

set(beams 20000)
foreach(part 0 1)
  run_in(${DIR}/work ${SPECTRACE} render scene.json --device cpu -q --no-png --beams ${beams} --shard ${part}/2
         -o part${part}.exr --state part${part}.state)
endforeach()
run_in(${DIR}/work ${SPECTRACE} render scene.json --device cpu -q --no-png --beams ${beams} -o whole.exr)

foreach(part 0 1)
  file(RENAME ${DIR}/work/part${part}.state ${DIR}/elsewhere/part${part}.state)
endforeach()
file(REMOVE ${DIR}/work/scene.json ${DIR}/work/spd/lamp.csv)

run_in(${DIR}/elsewhere ${SPECTRACE} merge part0.state part1.state --device cpu -q --no-png -o merged.exr
       --state merged.state)
expect_same(${DIR}/elsewhere/merged.exr ${DIR}/work/whole.exr)
run_in(${DIR}/elsewhere ${SPECTRACE} merge merged.state --device cpu -q --no-png -o again.exr)
expect_same(${DIR}/elsewhere/again.exr ${DIR}/work/whole.exr)
