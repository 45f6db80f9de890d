# A job's "state" is written as render --state writes it: two jobs with
# state patterns, each state merged (`merge`) and resumed (`render
# --resume`) to the pixels of the job's EXR and of a render of all the
# beams. A state onto another job's state, the job file or the job's own
# EXR is refused (exit 2, naming the line and /state); a job with
# overrides writes a state that merges alone, anywhere.
#   -DSPECTRACE=path  -DCOMPARE=exr_pixels_equal  -DSCENE=scenes/batch/lamp.json  -DDIR=scratch folder
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
set(quick --device cpu -q --no-png)
file(WRITE "${DIR}/jobs.jsonl"
  "{\"scene\": \"${SCENE}\", \"output\": \"a.exr\", \"beams\": 2000, \"seed\": 3, \"state\": \"a_{/lights/0/name}.state\"}\n"
  "{\"scene\": \"${SCENE}\", \"output\": \"b.exr\", \"beams\": 3000, \"seed\": 5, \"state\": \"states/b_{index}.state\"}\n")
run("${SPECTRACE}" batch "${DIR}/jobs.jsonl" ${quick})
foreach(state a_lamp.state states/b_0.state)
  if(NOT EXISTS "${DIR}/${state}")
    message(FATAL_ERROR "batch wrote no ${state}")
  endif()
endforeach()
run("${SPECTRACE}" merge "${DIR}/a_lamp.state" -o "${DIR}/merged_a.exr" ${quick})
run("${SPECTRACE}" merge "${DIR}/states/b_0.state" -o "${DIR}/merged_b.exr" ${quick})
expect_same("${DIR}/merged_a.exr" "${DIR}/a.exr")
expect_same("${DIR}/merged_b.exr" "${DIR}/b.exr")
# The first job's 2000 beams, resumed to 4000, are a render of 4000 beams.
run("${SPECTRACE}" render "${SCENE}" --seed 3 --beams 4000 --resume "${DIR}/a_lamp.state" --state "${DIR}/resumed.state"
    -o "${DIR}/resumed.exr" ${quick})
run("${SPECTRACE}" render "${SCENE}" --seed 3 --beams 4000 -o "${DIR}/whole.exr" ${quick})
expect_same("${DIR}/resumed.exr" "${DIR}/whole.exr")

file(WRITE "${DIR}/same_state.jsonl"
  "{\"scene\": \"${SCENE}\", \"output\": \"c.exr\", \"beams\": 1000, \"state\": \"c_{/render/seed}.state\"}\n"
  "{\"scene\": \"${SCENE}\", \"output\": \"d.exr\", \"beams\": 1000, \"state\": \"c_1.state\"}\n")
expect_refused(same_state "same_state.jsonl:2: /state: [^\n]*c_1.state is also the state of [^\n]*same_state.jsonl:1"
               "${SPECTRACE}" batch "${DIR}/same_state.jsonl" ${quick})
if(EXISTS "${DIR}/d.exr")
  message(FATAL_ERROR "the job refused for its state rendered")
endif()
file(WRITE "${DIR}/onto_jobs.jsonl"
  "{\"scene\": \"${SCENE}\", \"output\": \"e.exr\", \"beams\": 1000, \"state\": \"onto_jobs.jsonl\"}\n")
file(SHA256 "${DIR}/onto_jobs.jsonl" before)
expect_refused(state_onto_job_file "onto_jobs.jsonl:1: /state: state [^\n]*onto_jobs.jsonl is the input file"
               "${SPECTRACE}" batch "${DIR}/onto_jobs.jsonl" ${quick})
file(SHA256 "${DIR}/onto_jobs.jsonl" after)
if(NOT before STREQUAL after OR EXISTS "${DIR}/e.exr")
  message(FATAL_ERROR "the job file was overwritten, or the refused job rendered")
endif()
file(WRITE "${DIR}/own_output.jsonl"
  "{\"scene\": \"${SCENE}\", \"output\": \"g.exr\", \"beams\": 1000, \"state\": \"g.exr\"}\n")
expect_refused(state_onto_own_output "own_output.jsonl:1: /state: state [^\n]*g.exr is also this run's output"
               "${SPECTRACE}" batch "${DIR}/own_output.jsonl" ${quick})
# A job with "set" writes a state that carries its scene: merged alone in
# another folder it gives the job's pixels.
file(WRITE "${DIR}/set.jsonl"
  "{\"scene\": \"${SCENE}\", \"output\": \"f.exr\", \"state\": \"f.state\", \"set\": {\"/lights/0/power_w\": 2}}\n")
run("${SPECTRACE}" batch "${DIR}/set.jsonl" ${quick})
file(MAKE_DIRECTORY "${DIR}/elsewhere")
file(RENAME "${DIR}/f.state" "${DIR}/elsewhere/f.state")
execute_process(COMMAND "${SPECTRACE}" merge f.state -o f.exr -q --no-png WORKING_DIRECTORY "${DIR}/elsewhere"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the state of a job with \"set\" did not merge alone elsewhere (${rc}): ${err}")
endif()
expect_same("${DIR}/elsewhere/f.exr" "${DIR}/f.exr")
message(STATUS "batch states merge and resume like render's; clashing states were refused; a job with set writes one")
