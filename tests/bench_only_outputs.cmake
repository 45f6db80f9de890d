# `bench --only SECTION --out DIR` writes the CSV files of the sections it
# runs and no others: no other section's CSV, and no empty one (a header
# without rows), which a reader would take for a measurement of nothing.
#   -DCOMMAND=prog|arg|arg   the bench command, its --out DIR among the arguments
#   -DDIR=...                that DIR (emptied first)
#   -DEXPECT_CSV=a.csv|b.csv the CSV files the sections write, relative to DIR
#   -DEXPECT_REGEX=...       a regex the output must match
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
file(REMOVE_RECURSE "${DIR}")
string(REPLACE "|" ";" cmd "${COMMAND}")
expect_output(bench "${EXPECT_REGEX}" ${cmd})
string(REPLACE "|" ";" expected "${EXPECT_CSV}")
list(SORT expected)
file(GLOB_RECURSE found RELATIVE "${DIR}" "${DIR}/*.csv")
list(SORT found)
if(NOT found STREQUAL expected)
  message(FATAL_ERROR "expected exactly these CSV files in ${DIR}: ${expected}; found: ${found}")
endif()
foreach(csv IN LISTS found)
  file(STRINGS "${DIR}/${csv}" lines)
  list(LENGTH lines n)
  if(n LESS 2)
    message(FATAL_ERROR "${DIR}/${csv} has no rows (${n} lines)")
  endif()
endforeach()
message(STATUS "${DIR} holds ${found}, each with rows")
