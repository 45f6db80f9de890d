# cmake -DPROGRAM=... -P expect_leak.cmake
# Runs PROGRAM in the test's own environment (ASAN_OPTIONS from the caller,
# LSAN_OPTIONS with the suppressions from SPECTRACE_TEST_ENV) and succeeds
# only if LeakSanitizer reported exactly the leak the program makes: the
# program fails (exit code 23, or SIGABRT under abort_on_error=1), the report
# names spectraceLeakOnPurpose, and the summary counts its 256 bytes and
# nothing else. (CTest alone cannot accept an aborted process, whatever its
# output, hence this wrapper.)
execute_process(COMMAND "${PROGRAM}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
set(problems "")
if(rc STREQUAL "0")
  string(APPEND problems "  the program exited 0, so LeakSanitizer did not fail it\n")
endif()
if(NOT out MATCHES "ERROR: LeakSanitizer: detected memory leaks")
  string(APPEND problems "  no LeakSanitizer report\n")
endif()
if(NOT out MATCHES "in spectraceLeakOnPurpose")
  string(APPEND problems "  the report does not name spectraceLeakOnPurpose\n")
endif()
if(NOT out MATCHES "SUMMARY: AddressSanitizer: 256 byte\\(s\\) leaked in 1 allocation\\(s\\)")
  string(APPEND problems "  the summary is not exactly our 256 bytes in 1 allocation\n")
endif()
if(problems AND out MATCHES "<unknown module>")
  string(APPEND problems "  (a leak from <unknown module> is most likely the Vulkan driver's, reported because the "
    "driver was unloaded before the leak check: see tests/sanitizer/keep_vulkan_driver_loaded.cpp)\n")
endif()
if(problems)
  message(FATAL_ERROR "expected LeakSanitizer to report exactly our own leak (exit status: ${rc}):\n${problems}")
endif()
message("expect_leak: LeakSanitizer caught our own leak (exit status: ${rc})")
