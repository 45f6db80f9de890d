# A resume that cannot go on is refused with exit code 2 before anything is
# traced, naming the state file and the reason: another seed, a merged
# state, another first beam, more beams than the render.
#   -DSPECTRACE=path  -DSCENE=scene.json  -DDIR=scratch folder
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
set(quick --device cpu -q --no-png)
render_two_shards()
run("${SPECTRACE}" merge "${DIR}/part0.state" "${DIR}/part1.state" -q --no-png -o "${DIR}/merged.exr"
    --state "${DIR}/merged.state")

function(refused name regex)
  expect_refused("${name}" "${regex}" "${SPECTRACE}" render "${SCENE}" ${quick} -o "${DIR}/${name}.exr" ${ARGN})
endfunction()

set(part0 "${DIR}/part0.state")
refused(another_seed "cannot resume from .*part0.state: it belongs to another render: it differs in seed"
        --beams 2000 --seed 99 --resume "${part0}")
refused(merged "cannot resume from .*merged.state: it holds 2 beam ranges \\(a merged state\\)"
        --beams 2000 --resume "${DIR}/merged.state")
refused(fewer_beams "cannot resume from .*part0.state: it holds 1000 beams, more than this render's 500"
        --beams 500 --resume "${part0}")
refused(another_start "cannot resume from .*part1.state: its beams start at beam 1000, this render's at beam 0"
        --beams 2000 --resume "${DIR}/part1.state")
message(STATUS "every resume refusal named its state file and why")
