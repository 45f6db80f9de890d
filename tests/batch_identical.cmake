# A batch renders each job exactly as `spectrace render` renders it alone,
# and `render a.json b.json -o DIR/` exactly as one render per scene, though
# the batch reuses device buffers and writes each job while the next traces
# (mixed shapes: sensors, bins, spot/disk/rect lights, pinhole and bare):
# the EXRs' pixel data are compared bit for bit (exr_pixels_equal).
# -DSPECTRACE=... -DEXR_EQUAL=... -DSOURCE_DIR=... -DOUT=... -DDEVICE=gpu|cpu
cmake_minimum_required(VERSION 3.25)
set(data ${SOURCE_DIR}/tests/data/batch)
file(REMOVE_RECURSE ${OUT})

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(JOIN " " line ${ARGN})
    message(FATAL_ERROR "${line}: exit code ${rc}\n${out}\n${err}")
  endif()
endfunction()

run(${SPECTRACE} batch ${data}/identical.jsonl --out-dir ${OUT}/batch --device ${DEVICE} -q --no-png)
run(${SPECTRACE} render ${SOURCE_DIR}/scenes/batch/lamp.json ${SOURCE_DIR}/scenes/reference/disk_off_axis.json
    -o ${OUT}/several/ --beams 200000 --seed 5 --device ${DEVICE} -q --no-png)

# batch output | scene rendered alone
set(pairs
  "batch/sweep_0_2700K.exr|${SOURCE_DIR}/scenes/batch/lamp.json"
  "batch/sweep_1_4000K.exr|${data}/lamp_4000k.json"
  "batch/far.exr|${data}/lamp_far.json"
  "batch/disk.exr|${SOURCE_DIR}/scenes/reference/disk_off_axis.json"
  "batch/rect.exr|${SOURCE_DIR}/scenes/reference/pinhole_rect.json"
  "several/lamp.exr|${SOURCE_DIR}/scenes/batch/lamp.json"
  "several/disk_off_axis.exr|${SOURCE_DIR}/scenes/reference/disk_off_axis.json")
set(index 0)
foreach(pair IN LISTS pairs)
  string(REPLACE "|" ";" parts "${pair}")
  list(GET parts 0 output)
  list(GET parts 1 scene)
  set(alone ${OUT}/alone/${index}.exr)
  run(${SPECTRACE} render ${scene} -o ${alone} --beams 200000 --seed 5 --device ${DEVICE} -q --no-png)
  run(${EXR_EQUAL} ${OUT}/${output} ${alone})
  math(EXPR index "${index} + 1")
endforeach()
