# Every output flag pointed at each kind of input (the scene, its OBJ mesh,
# an input state, the job file, another output of the same run, a device,
# a folder) is refused with exit code 2 before anything is traced, and every
# input stays byte-identical.
#   -DSPECTRACE=path  -DSCENE_DIR=scenes/  -DDIR=scratch folder
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}/folder")
configure_file("${SCENE_DIR}/prism.json" "${DIR}/scene.json" COPYONLY)
configure_file("${SCENE_DIR}/prism.obj" "${DIR}/prism.obj" COPYONLY)
set(quick --device cpu --beams 1000 -q)
run("${SPECTRACE}" render "${DIR}/scene.json" ${quick} --no-png -o "${DIR}/in.exr" --state "${DIR}/in.state")
file(WRITE "${DIR}/jobs.png" "{\"scene\": \"scene.json\", \"output\": \"jobs.exr\", \"beams\": 1000}\n")
set(inputs scene.json prism.obj in.state in.exr jobs.png)
foreach(input IN LISTS inputs)
  file(SHA256 "${DIR}/${input}" before_${input})
endforeach()

# Refused with exit 2 and the message, and every input unchanged.
function(refused name regex)
  expect_refused("${name}" "${regex}" "${SPECTRACE}" ${ARGN})
  foreach(input IN LISTS inputs)
    file(SHA256 "${DIR}/${input}" after)
    if(NOT after STREQUAL before_${input})
      message(FATAL_ERROR "${name}: ${input} changed")
    endif()
  endforeach()
endfunction()

set(render render "${DIR}/scene.json" ${quick})
refused(state_onto_scene "--state .*scene.json is the input file" ${render} -o "${DIR}/a.exr" --state "${DIR}/scene.json")
refused(state_onto_mesh "--state .*prism.obj is the input file" ${render} -o "${DIR}/a.exr" --state "${DIR}/prism.obj")
refused(state_onto_exr "--state .*in.exr is also this run's output" ${render} -o "${DIR}/in.exr" --state "${DIR}/in.exr")
refused(state_onto_png "--state .*a.png is also this run's PNG preview" ${render} -o "${DIR}/a.exr" --state "${DIR}/a.png")
refused(state_onto_device "--state /dev/null exists and is not a regular file" ${render} -o "${DIR}/a.exr" --state /dev/null)
refused(state_onto_folder "--state .*folder exists and is not a regular file \\(a folder\\)" ${render} -o "${DIR}/a.exr" --state "${DIR}/folder")
refused(resumed_state_onto_scene "--state .*scene.json is the input file" ${render} -o "${DIR}/a.exr" --resume "${DIR}/in.state" --state "${DIR}/scene.json")
refused(output_onto_scene "output .*scene.json is the input file" ${render} -o "${DIR}/scene.json")
refused(merge_state_onto_input "--state .*in.state is the input file" merge "${DIR}/in.state" -q -o "${DIR}/m.exr" --state "${DIR}/in.state")
refused(merge_output_onto_input "--state .*in.exr is also this run's output" merge "${DIR}/in.state" -q -o "${DIR}/in.exr" --state "${DIR}/in.exr")
# A link is replaced by the atomic write rather than written through (a link
# to /dev/stdout became a regular file): refused, the link and its target kept.
file(CREATE_LINK "${DIR}/in.exr" "${DIR}/link.state" SYMBOLIC)
refused(state_onto_link "--state .*link.state is a symbolic link \\(to .*in.exr\\)" ${render} -o "${DIR}/a.exr" --state "${DIR}/link.state")
if(NOT IS_SYMLINK "${DIR}/link.state")
  message(FATAL_ERROR "state_onto_link: the link was replaced")
endif()
file(CREATE_LINK "${DIR}/nowhere.exr" "${DIR}/dangling.exr" SYMBOLIC)
refused(output_onto_dangling_link "output .*dangling.exr is a symbolic link" ${render} -o "${DIR}/dangling.exr")
refused(batch_preview_onto_job_file "PNG preview .*jobs.png is the input file .*jobs.png" batch "${DIR}/jobs.png" -q --device cpu)
message(STATUS "every output onto an input was refused, and the inputs are unchanged")
