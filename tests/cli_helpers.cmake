# Helpers of the CLI test scripts (cli_state.cmake, cli_mpi.cmake), included
# by them; COMPARE is tools/exr_pixels_equal.

# Runs a command; fails the test with its output unless it exits 0.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}${err}")
  endif()
endfunction()

# Fails the test unless two EXR files' pixel data are bit-identical.
function(expect_same a b)
  execute_process(COMMAND ${COMPARE} ${a} ${b} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${a} and ${b} differ: ${out}")
  endif()
endfunction()
