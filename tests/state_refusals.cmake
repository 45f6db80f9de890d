# State files that are wrong are refused with exit code 2 before anything is
# written, naming the file and the header field: a 16 GiB sparse file (no
# magic, or a valid state grown), a range that wraps past 2^64, ranges of one
# state that overlap, more counted beams than the ranges hold, and merges
# whose counters or beams would pass 2^64 - 1.
#   -DSPECTRACE=path  -DCRAFT=craft_state  -DSCENE=scene.json  -DDIR=scratch folder
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
set(quick --device cpu -q --no-png)
# A plain film (one wavelength a beam): counters of one word, whose sums
# pass 2^64 - 1.
set(shard_args --wavelengths-per-beam 1)
render_two_shards()
set(part0 "${DIR}/part0.state")
set(part1 "${DIR}/part1.state")

# `merge` of the given states refused with a message matching `regex`, and
# neither of its outputs written.
function(merge_refused name regex)
  expect_refused("${name}" "${regex}" "${SPECTRACE}" merge ${ARGN} ${quick} -o "${DIR}/${name}.exr"
                 --state "${DIR}/${name}_merged.state")
  foreach(output ${name}.exr ${name}_merged.state)
    if(EXISTS "${DIR}/${output}")
      message(FATAL_ERROR "${name}: ${output} was written by a refused merge")
    endif()
  endforeach()
endfunction()

# The crafted files are valid but for the field they change: unchanged,
# one merges.
run("${CRAFT}" "${part0}" "${DIR}/copy.state" ranges=0:1000)
run("${SPECTRACE}" merge "${DIR}/copy.state" "${part1}" ${quick} -o "${DIR}/control.exr")

# 16 GiB sparse files (no disk space used): refused at once by their magic or
# by the size the header implies, not read whole into memory.
set(refuse_timeout 30)
run(truncate -s 16G "${DIR}/zeros.state")
merge_refused(zeros_16g "spectrace: error: [^\n]*zeros.state: not a spectrace state file \\(no SPCTRSTA magic\\)"
              "${DIR}/zeros.state" "${part1}")
file(REMOVE "${DIR}/zeros.state")
file(COPY_FILE "${part0}" "${DIR}/grown.state")
run(truncate -s 16G "${DIR}/grown.state")
set(grown "spectrace: error: [^\n]*grown.state: the file is 17179869184 bytes, but its header implies [0-9]+: ")
merge_refused(grown_16g "${grown}.*it is truncated or has bytes after its end" "${part1}" "${DIR}/grown.state")
expect_refused(resume_grown_16g "${grown}" "${SPECTRACE}" render "${SCENE}" ${quick} --beams 2000
               --resume "${DIR}/grown.state" --state "${DIR}/resumed.state" -o "${DIR}/resumed.exr")
file(REMOVE "${DIR}/grown.state")
unset(refuse_timeout)

# Beams 2000 to 2^64 + 999 wrap to 0..999, part 0's: the sum of the ranges
# wrapped to 1000 beams for a film of 2000, an image twice too bright.
run("${CRAFT}" "${part1}" "${DIR}/wraps.state" ranges=1000:1000,2000:18446744073709550616)
merge_refused(wraps "[^\n]*wraps.state: /ranges/1: \\[2000, \\+18446744073709550616\\) runs past beam 2\\^64 - 1"
              "${part0}" "${DIR}/wraps.state")
run("${CRAFT}" "${part0}" "${DIR}/overlap.state" ranges=0:600,500:500)
merge_refused(overlap "[^\n]*overlap.state: /ranges/1: \\[500, \\+500\\) and /ranges/0 \\[0, \\+600\\) share beam 500"
              "${DIR}/overlap.state" "${part1}")
run("${CRAFT}" "${part0}" "${DIR}/counted.state" counted_beams=1001)
merge_refused(counted "[^\n]*counted.state: /counted_beams: 1001 beams counted, more than the 1000 beams of /ranges"
              "${DIR}/counted.state" "${part1}")

# Merges whose sums would wrap: every count to exactly 2^64, so to 0 (the
# merged image was all black), and the beams of the ranges.
run("${CRAFT}" "${part1}" "${DIR}/wrapping.state" "counts_wrapping=${part0}")
merge_refused(counts_overflow "cannot merge [^\n]*wrapping.state with [^\n]*part0.state: counts at pixel \\([0-9]+, [0-9]+\\), bin [0-9]+: [1-9][0-9]* \\+ [1-9][0-9]* passes 2\\^64 - 1"
              "${part0}" "${DIR}/wrapping.state")
run("${CRAFT}" "${part0}" "${DIR}/low.state" ranges=0:9223372036854775808)
run("${CRAFT}" "${part1}" "${DIR}/high.state" ranges=9223372036854775808:9223372036854775808)
merge_refused(beams_overflow "cannot merge [^\n]*high.state with [^\n]*low.state: /ranges: 9223372036854775808 \\+ 9223372036854775808 beams pass 2\\^64 - 1"
              "${DIR}/low.state" "${DIR}/high.state")
message(STATUS "every bad state was refused, naming its file and field, with nothing written")
