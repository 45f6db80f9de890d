# Every verb's --help: flags without CLI11's "{false}", options with a type
# name (no bare TEXT: numbers, paths and devices say which), and the
# defaults that are fixed values shown after '='.
#   -DSPECTRACE=path -DREADME=path
foreach(verb render merge batch bench measure)
  execute_process(COMMAND "${SPECTRACE}" ${verb} --help RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${verb} --help: exit code ${rc}:\n${out}${err}")
  endif()
  if(out MATCHES "\\{(true|false)\\}")
    message(FATAL_ERROR "${verb} --help shows a flag with its value in braces:\n${out}")
  endif()
  if(out MATCHES "TEXT")
    message(FATAL_ERROR "${verb} --help shows an option's type as TEXT:\n${out}")
  endif()
  set(help_${verb} "${out}")
endforeach()
# Some of the type names and defaults that must be there.
foreach(case "render|--beams COUNT " "render|--seed INT " "render|--first-beam INT=0 "
             "render|--threads COUNT " "render|--checkpoint-seconds SECONDS=60"
             "render|--device DEVICE:{auto,gpu,cpu}=auto" "render|--cpu-code CODE:{auto,baseline,x86-64-v3}=auto"
             "render|--no-png  " "render|--state PATH " "render|scene PATH ... REQUIRED" "render|--set POINTER=JSON ... "
             "merge|--no-png  " "merge|-o,--output PATH REQUIRED" "batch|--no-pipeline-cache  "
             "batch|--out-dir DIR " "bench|--beams COUNT=33554432 " "bench|--profile-beams COUNT=8388608")
  string(FIND "${case}" "|" bar)
  string(SUBSTRING "${case}" 0 ${bar} verb)
  math(EXPR bar "${bar} + 1")
  string(SUBSTRING "${case}" ${bar} -1 text)
  string(FIND "${help_${verb}}" "${text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${verb} --help does not show '${text}':\n${help_${verb}}")
  endif()
endforeach()
# The README's usage of bench names exactly the options its help shows, so
# that neither falls behind the other.
string(REGEX MATCHALL "\n +(-[a-z],)?--[a-z-]+" help_options "${help_bench}")
list(TRANSFORM help_options REPLACE "^\n +(-[a-z],)?" "")
list(REMOVE_ITEM help_options --help)
file(READ "${README}" readme)
string(REGEX MATCH "\nspectrace bench [^\n]*(\n +\\[[^\n]*)*" usage "${readme}")
string(REGEX MATCHALL "--[a-z-]+" readme_options "${usage}")
list(SORT help_options)
list(SORT readme_options)
if(NOT help_options OR NOT help_options STREQUAL readme_options)
  message(FATAL_ERROR "README's `spectrace bench` usage names ${readme_options}\nbut bench --help shows ${help_options}")
endif()
message(STATUS "every verb's help shows type names and defaults, and flags without braces; README's bench usage matches its help")
