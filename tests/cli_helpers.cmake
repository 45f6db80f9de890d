# Helpers of the CLI test scripts (cli_state.cmake, cli_mpi.cmake,
# outputs_never_inputs.cmake, resume_refusals.cmake, merge_messages.cmake, resume_rate.cmake,
# state_refusals.cmake, bench_only_outputs.cmake, batch_state.cmake, cli_set_option.cmake,
# referenced_files_changed.cmake, state_bundle.cmake),
# included by them; COMPARE is tools/exr_pixels_equal.

# Runs a command; fails the test with its output unless it exits 0.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}${err}")
  endif()
endfunction()

# Fails the test (naming the case `name`) unless the command exits 0 with
# output matching `regex`; the output is left in `output` for the caller.
function(expect_output name regex)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: exit code ${rc}:\n${out}${err}")
  endif()
  if(NOT "${out}${err}" MATCHES "${regex}")
    message(FATAL_ERROR "${name}: the output does not match '${regex}':\n${out}${err}")
  endif()
  set(output "${out}${err}" PARENT_SCOPE)
endfunction()

# Fails the test unless two EXR files' pixel data are bit-identical.
function(expect_same a b)
  execute_process(COMMAND ${COMPARE} ${a} ${b} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${a} and ${b} differ: ${out}")
  endif()
endfunction()

# Fails the test (naming the case `name`) unless the command exits 2 (bad
# input) with output matching `regex`, within `refuse_timeout` seconds when
# the caller sets it (240 otherwise).
function(expect_refused name regex)
  if(NOT DEFINED refuse_timeout)
    set(refuse_timeout 240)
  endif()
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT ${refuse_timeout})
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "${name}: exit code ${rc}, expected 2:\n${out}${err}")
  endif()
  if(NOT "${out}${err}" MATCHES "${regex}")
    message(FATAL_ERROR "${name}: the message does not match '${regex}':\n${out}${err}")
  endif()
endfunction()

# Two shards of SCENE, 1000 beams each, on the CPU reference: DIR/part0 and
# DIR/part1, each an .exr and a .state; `shard_args`, when the caller sets
# it, goes to both renders.
function(render_two_shards)
  foreach(part 0 1)
    run("${SPECTRACE}" render "${SCENE}" --device cpu -q --no-png --beams 2000 --shard ${part}/2 ${shard_args}
        -o "${DIR}/part${part}.exr" --state "${DIR}/part${part}.state")
  endforeach()
endfunction()
