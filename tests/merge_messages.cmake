# What merge prints: the count of states and beams it merged, in words that
# agree with the numbers ("1 state", "2 states"); and when the scene a state
# without its bundle was rendered from is gone, its path as the render was
# given it and the absolute path looked for (a state with its bundle needs
# no scene file).
#   -DSPECTRACE=path  -DCRAFT=craft_state  -DSCENE=scene.json  -DDIR=scratch folder
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
set(quick --device cpu --no-png)
foreach(part 0 1)
  run("${SPECTRACE}" render "${SCENE}" ${quick} -q --beams 2000 --shard ${part}/2 -o "${DIR}/part${part}.exr"
      --state "${DIR}/part${part}.state")
endforeach()

# Merges the states and fails unless the output matches `regex`.
function(merged regex)
  expect_output("merge ${ARGN}" "${regex}" "${SPECTRACE}" merge ${ARGN} ${quick} -o "${DIR}/merged.exr")
endfunction()
merged("spectrace: merged 1 state, 1000 beams -> " "${DIR}/part0.state")
merged("spectrace: merged 2 states, 2000 beams -> " "${DIR}/part0.state" "${DIR}/part1.state")

# A state of a render given a relative scene path, merged once that scene is gone.
configure_file("${SCENE}" "${DIR}/gone.json" COPYONLY)
execute_process(COMMAND "${SPECTRACE}" render gone.json ${quick} -q --beams 1000 -o gone.exr --state gone.state
                WORKING_DIRECTORY "${DIR}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "render gone.json: exit code ${rc}:\n${out}${err}")
endif()
file(REMOVE "${DIR}/gone.json")
run("${SPECTRACE}" merge "${DIR}/gone.state" ${quick} -q -o "${DIR}/gone_merged.exr")
run("${CRAFT}" "${DIR}/gone.state" "${DIR}/gone_unbundled.state" drop_bundle)
expect_refused(scene_gone
  "spectrace: error: cannot read the scene the state was rendered from: gone.json: scene file not found \\(looked for /[^)]*/gone.json\\)"
  "${SPECTRACE}" merge "${DIR}/gone_unbundled.state" ${quick} -o "${DIR}/gone_merged.exr")
message(STATUS "merge counted its states and beams in words that agree, and named the scene it could not read")
