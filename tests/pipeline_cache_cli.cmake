# --pipeline-cache and --no-pipeline-cache on render and batch: the default
# file under $XDG_CACHE_HOME/spectrace, an explicit file, nothing at all when
# off, and a corrupt file ignored with a warning without changing the pixels.
# -DSPECTRACE=... -DEXR_EQUAL=... -DSOURCE_DIR=... -DOUT=...
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(scene ${SOURCE_DIR}/scenes/batch/lamp.json)
set(common --beams 100000 --seed 3 --device gpu --no-png)

function(run xdg)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env XDG_CACHE_HOME=${xdg} ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(JOIN " " line ${ARGN})
    message(FATAL_ERROR "${line}: exit code ${rc}\n${out}\n${err}")
  endif()
  set(stderr "${err}" PARENT_SCOPE)
endfunction()

# Off: nothing is written, for render and for batch.
run(${OUT}/xdg_off ${SPECTRACE} render ${scene} -o ${OUT}/off.exr ${common} -q --no-pipeline-cache)
run(${OUT}/xdg_off ${SPECTRACE} batch ${SOURCE_DIR}/tests/data/batch/identical.jsonl --out-dir ${OUT}/batch_off
    --device gpu -q --no-png --no-pipeline-cache)
if(EXISTS ${OUT}/xdg_off)
  message(FATAL_ERROR "--no-pipeline-cache wrote ${OUT}/xdg_off")
endif()

# Default location, keyed by device UUID and driver version.
run(${OUT}/xdg_on ${SPECTRACE} render ${scene} -o ${OUT}/on.exr ${common} -q)
file(GLOB cached ${OUT}/xdg_on/spectrace/pipelines-*-*.bin)
if(NOT cached)
  message(FATAL_ERROR "no pipeline cache under ${OUT}/xdg_on/spectrace")
endif()
run(${OUT}/xdg_on ${SPECTRACE} render ${scene} -o ${OUT}/on_again.exr ${common})
if(stderr MATCHES "pipeline cache")
  message(FATAL_ERROR "a valid cache must be used silently:\n${stderr}")
endif()

# An explicit file, from render and from batch.
run(${OUT}/xdg_explicit ${SPECTRACE} render ${scene} -o ${OUT}/explicit.exr ${common} -q
    --pipeline-cache ${OUT}/explicit.bin)
run(${OUT}/xdg_explicit ${SPECTRACE} batch ${SOURCE_DIR}/tests/data/batch/identical.jsonl --out-dir ${OUT}/batch_on
    --device gpu -q --no-png --pipeline-cache ${OUT}/batch.bin)
foreach(f explicit.bin batch.bin)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "--pipeline-cache did not write ${OUT}/${f}")
  endif()
endforeach()
if(EXISTS ${OUT}/xdg_explicit)
  message(FATAL_ERROR "--pipeline-cache PATH must not write the default cache")
endif()

# A corrupt file: a warning, the same pixels, and a valid cache in its place.
file(WRITE ${OUT}/corrupt.bin "this is not a Vulkan pipeline cache, just some bytes that are long enough")
run(${OUT}/xdg_corrupt ${SPECTRACE} render ${scene} -o ${OUT}/corrupt.exr ${common}
    --pipeline-cache ${OUT}/corrupt.bin)
if(NOT stderr MATCHES "pipeline cache [^\n]*corrupt.bin ignored: ")
  message(FATAL_ERROR "no warning about the corrupt cache:\n${stderr}")
endif()
file(READ ${OUT}/explicit.bin good HEX LIMIT 32)
file(READ ${OUT}/corrupt.bin replaced HEX LIMIT 32)
if(NOT good STREQUAL replaced)
  message(FATAL_ERROR "the corrupt cache was not replaced by a valid one")
endif()
foreach(exr on.exr on_again.exr explicit.exr corrupt.exr)
  execute_process(COMMAND ${EXR_EQUAL} ${OUT}/off.exr ${OUT}/${exr} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${exr} differs from the render without a pipeline cache")
  endif()
endforeach()
