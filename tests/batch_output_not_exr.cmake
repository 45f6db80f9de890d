# A job's output that is not an .exr, made by a placeholder of its output
# pattern, is refused (exit 2, naming the line and /output), also with
# --skip-existing when a complete EXR already has that name (this used to
# skip it as complete, exit 0), and nothing is written; so is an output
# holding a NUL character.
#   -DSPECTRACE=path  -DSOURCE_DIR=repository  -DDIR=scratch folder
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
set(jobs "${SOURCE_DIR}/tests/data/batch/output_not_exr.jsonl")
# The pattern "{/lights/0/name}" names the output "lamp", after the light.
run("${SPECTRACE}" render "${SOURCE_DIR}/scenes/batch/lamp.json" --device cpu -q --no-png --beams 1000 -o "${DIR}/lamp.exr")
file(RENAME "${DIR}/lamp.exr" "${DIR}/lamp")
file(SHA256 "${DIR}/lamp" before)
set(regex "output_not_exr.jsonl:1: /output: output [^\n]*lamp \\(from the pattern \"{/lights/0/name}\"\\) must end in .exr")
expect_refused(not_exr "${regex}" "${SPECTRACE}" batch "${jobs}" --out-dir "${DIR}" --device cpu -q)
expect_refused(not_exr_skip_existing "${regex}" "${SPECTRACE}" batch "${jobs}" --out-dir "${DIR}" --device cpu -q --skip-existing)
# "a\u0000b.exr" would be cut to "a" where the system reads it: the EXR
# and then its PNG preview went there (exit 0).
expect_refused(nul "output_nul.jsonl:1: /output: output .a.u0000b.exr. holds a NUL character"
               "${SPECTRACE}" batch "${SOURCE_DIR}/tests/data/batch/output_nul.jsonl" --out-dir "${DIR}" --device cpu -q)
file(SHA256 "${DIR}/lamp" after)
if(NOT before STREQUAL after OR EXISTS "${DIR}/lamp.png" OR EXISTS "${DIR}/a")
  message(FATAL_ERROR "a refused output was written")
endif()
message(STATUS "an output pattern making no .exr, and one holding a NUL, were refused")
