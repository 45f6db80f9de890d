# The summary of a resumed render gives the rate of the beams traced in
# this run, not of all the film's beams over this run's time, and says how
# many the state held: a state of 1000 beams resumed to 2000 traces 1000;
# a finished state resumed traces none.
#   -DSPECTRACE=path  -DSCENE=scene.json  -DDIR=scratch folder
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
render_two_shards()

function(summary_matches name regex)
  expect_output("${name}" "${regex}" "${SPECTRACE}" render "${SCENE}" --device cpu --no-png -o "${DIR}/${name}.exr"
                ${ARGN})
  set(summary "${output}" PARENT_SCOPE)
endfunction()
# part0.state holds beams [0, 1000); the resumed render of 2000 traces 1000.
summary_matches(resumed "spectrace: 1000 beams in [0-9.]+ s \\([0-9.]+ Mbeam/s\\) on [^\n]*, after 1000 resumed from the state\n"
                --beams 2000 --resume "${DIR}/part0.state")
# A resume keeps writing its state, so part0.state now holds 2000 beams:
# resumed at 2000, it is finished and traces none.
summary_matches(finished "spectrace: 0 beams in [0-9.]+ s \\(0.0 Mbeam/s\\) on [^\n]*, after 2000 resumed from the state\n"
                --beams 2000 --resume "${DIR}/part0.state")
summary_matches(fresh "spectrace: 1000 beams in [0-9.]+ s \\([0-9.]+ Mbeam/s\\) on [^\n]*\n" --beams 1000)
if("${summary}" MATCHES "resumed")
  message(FATAL_ERROR "fresh: a render that resumed nothing says it did:\n${summary}")
endif()
message(STATUS "the resumed renders' summaries count this run's beams")
