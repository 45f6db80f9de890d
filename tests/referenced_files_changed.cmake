# A file the scene names (here its OBJ mesh) that changes between two
# renders keeps their films apart: merging the two states and resuming the
# older one are refused with exit code 2 naming referenced_files_sha256,
# where before the films were summed (exit 0). A state carries the mesh it
# was rendered with, so it develops alone whatever the file holds now; one
# without its bundle (as states were before they carried one) develops from
# the file, and is refused while the file differs.
#   -DSPECTRACE=path  -DCRAFT=craft_state  -DCOMPARE=exr_pixels_equal  -DSCENE_DIR=scenes/  -DDIR=scratch folder
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
configure_file("${SCENE_DIR}/prism.json" "${DIR}/scene.json" COPYONLY)
configure_file("${SCENE_DIR}/prism.obj" "${DIR}/prism.obj" COPYONLY)
set(SCENE "${DIR}/scene.json")
run("${SPECTRACE}" render "${SCENE}" --device cpu -q --no-png --beams 2000 --shard 0/2
    -o "${DIR}/part0.exr" --state "${DIR}/part0.state")
# The same scene file, its mesh file edited (a comment appended: other bytes).
file(READ "${DIR}/prism.obj" mesh)
file(APPEND "${DIR}/prism.obj" "# edited\n")
run("${SPECTRACE}" render "${SCENE}" --device cpu -q --no-png --beams 2000 --shard 1/2
    -o "${DIR}/part1.exr" --state "${DIR}/part1.state")
expect_refused(merge "cannot merge .*: they differ in referenced_files_sha256"
               "${SPECTRACE}" merge "${DIR}/part0.state" "${DIR}/part1.state" -q --no-png -o "${DIR}/m.exr")
expect_refused(resume "cannot resume from .*part0.state: it belongs to another render: it differs in referenced_files_sha256"
               "${SPECTRACE}" render "${SCENE}" --device cpu -q --no-png --beams 2000 -o "${DIR}/r.exr"
               --resume "${DIR}/part0.state")
run("${SPECTRACE}" merge "${DIR}/part0.state" -q --no-png -o "${DIR}/bundled.exr")
run("${CRAFT}" "${DIR}/part0.state" "${DIR}/unbundled.state" drop_bundle)
expect_refused(develop "a file the scene .*scene.json names \\(an OBJ mesh or CSV\\) has changed"
               "${SPECTRACE}" merge "${DIR}/unbundled.state" -q --no-png -o "${DIR}/d.exr")
# Put back, the mesh merges again.
file(WRITE "${DIR}/prism.obj" "${mesh}")
run("${SPECTRACE}" merge "${DIR}/unbundled.state" -q --no-png -o "${DIR}/d.exr")
# The bundled mesh was the one the state was rendered with.
expect_same("${DIR}/bundled.exr" "${DIR}/d.exr")
message(STATUS "states of another mesh were refused by merge, resume and develop")
