# What a render says before it traces, and after (stderr to a file):
# - a light never sampled is noted before the progress line, by its name;
# - with objects, when no light can shine on the camera directly, a note
#   says so before tracing, and a black image gets a warning after it.
# Before, the notes came after the render, named lights by index only, and
# a light hidden by objects gave a black image without a word.
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(READ "${SCENE}" lamp)

# Renders ${DIR}/<name>.json on the CPU; its stderr in `log`.
macro(render_log name)
  execute_process(COMMAND ${SPECTRACE} render ${DIR}/${name}.json --device cpu -o ${DIR}/${name}.exr --no-png
                  RESULT_VARIABLE rc ERROR_VARIABLE log TIMEOUT 240)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: exit code ${rc}:\n${log}")
  endif()
endmacro()

# Fails with `what` unless the last log matches `regex`.
function(expect_log regex what)
  if(NOT log MATCHES "${regex}")
    message(FATAL_ERROR "${what}:\n${log}")
  endif()
endfunction()

# A second light, "dark", of zero power: never sampled.
string(REPLACE "\"lights\": [" "\"lights\": [{\"name\": \"dark\", \"type\": \"point\", \"position\": [0, 0, 1], \"power_w\": 0, \"spd\": {\"blackbody_k\": 3000}}," two "${lamp}")
file(WRITE "${DIR}/two.json" "${two}")
render_log(two)
expect_log("spectrace: note: light \"dark\" \\(/lights/0, point, blackbody 3000 K\\) is never sampled: its power is zero\n(spectrace: [^\n]*\n)*spectrace: 100.0%"
           "no note naming light \"dark\" before the progress line")

# The lamp turned away from the camera, behind a grey plate it cannot light.
string(REPLACE "\"direction\": [-0.05, -0.02, -1.0]" "\"direction\": [0, 0, 1]" away "${lamp}")
string(REPLACE "\"render\":" "\"objects\": [{\"type\": \"rect\", \"center\": [0, 0, 0.5], \"normal\": [0, 0, -1], \"u_axis\": [1, 0, 0], \"size_m\": [0.2, 0.2], \"material\": {\"type\": \"diffuse\", \"reflectance\": 0.5}}], \"render\":" away "${away}")
file(WRITE "${DIR}/away.json" "${away}")
render_log(away)
expect_log("spectrace: note: no light can shine on the camera directly \\(light \"lamp\" \\(/lights/0, spot, [^)]*\\): [^)]*\\); only what the objects scatter can reach it\n(spectrace: [^\n]*\n)*spectrace: 100.0%"
           "no note before tracing that no light shines on the camera")
expect_log("spectrace: warning: no light reached the camera in 200000 beams: the image is black\n"
           "no warning that nothing was counted")
