# Fails when a scene file in scenes/ is missing from the whole-program test
# list (tests/CMakeLists.txt), so "the CLI renders every scene" stays true.
file(GLOB_RECURSE found RELATIVE ${SCENES_DIR} ${SCENES_DIR}/*.json)
cmake_minimum_required(VERSION 3.25)
foreach(file IN LISTS found)
  string(REGEX REPLACE "\\.json$" "" scene ${file})
  if(NOT scene IN_LIST LISTED)
    message(FATAL_ERROR "scenes/${file} is not rendered by the whole-program tests; add it to tests/CMakeLists.txt")
  endif()
endforeach()
