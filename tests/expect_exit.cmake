# Runs a command and checks its exit code and output (CTest alone can only
# tell zero from non-zero).
#   -DCOMMAND=prog|arg|arg   the command, arguments separated by '|'
#   -DEXPECT_CODE=2          the exit code it must return
#   -DEXPECT_REGEX=...       a regex its stdout+stderr must match
#   -DUNCHANGED=file         (optional) a file that must be byte-identical after
#   -DSETUP_COPY=src|dst     (optional) copy src to dst first (a fresh input)
if(DEFINED SETUP_COPY)
  string(REPLACE "|" ";" copy "${SETUP_COPY}")
  list(GET copy 0 src)
  list(GET copy 1 dst)
  get_filename_component(dir "${dst}" DIRECTORY)
  file(MAKE_DIRECTORY "${dir}")
  configure_file("${src}" "${dst}" COPYONLY)
endif()
if(DEFINED UNCHANGED)
  file(SHA256 "${UNCHANGED}" before)
endif()
string(REPLACE "|" ";" cmd "${COMMAND}")
execute_process(COMMAND ${cmd} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(all "${out}${err}")
if(NOT code STREQUAL "${EXPECT_CODE}")
  message(FATAL_ERROR "exit code ${code}, expected ${EXPECT_CODE}; output:\n${all}")
endif()
if(NOT all MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "output does not match '${EXPECT_REGEX}':\n${all}")
endif()
if(DEFINED UNCHANGED)
  file(SHA256 "${UNCHANGED}" after)
  if(NOT before STREQUAL after)
    message(FATAL_ERROR "${UNCHANGED} changed")
  endif()
endif()
message(STATUS "exit ${code} as expected: ${all}")
