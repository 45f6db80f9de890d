# cmake -DSOURCE_DIR=<repo> -DGRAPH=<module_graph.cmake> -P CheckLayering.cmake
# (GRAPH sets MODULES, each <module>_DEPS and VULKAN_MODULES; the top-level
# CMakeLists.txt writes it.)
# Fails when a file of host/<module>/ (tests excepted)
#  - includes a header of another host module that <module> does not name
#    among its own dependencies (not through theirs: a module says what it
#    uses, so the graph is what the code does, and a new back-arrow or
#    shortcut stops the build instead of creeping in); or
#  - includes a Vulkan header (<vulkan/...>) outside VULKAN_MODULES: the
#    device stays behind the backend's Device interface.
cmake_minimum_required(VERSION 3.25)
include(${GRAPH})

set(violations "")
foreach(module IN LISTS MODULES)
  set(allowed ${${module}_DEPS})
  # A lint over what is on disk, not a source list: globbing is right here.
  file(GLOB files RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/host/${module}/*.h ${SOURCE_DIR}/host/${module}/*.cpp)
  foreach(file IN LISTS files)
    if(file MATCHES "_test\\.cpp$")
      continue()
    endif()
    file(STRINGS ${SOURCE_DIR}/${file} includes REGEX "^#include \"[a-z_]+/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include \"([a-z_]+)/.*" "\\1" target "${line}")
      if(target STREQUAL module OR NOT target IN_LIST MODULES)
        continue()
      endif()
      if(NOT target IN_LIST allowed)
        string(APPEND violations "\n  ${file}: ${line} (module ${module} does not depend on ${target})")
      endif()
    endforeach()
    if(NOT module IN_LIST VULKAN_MODULES)
      file(STRINGS ${SOURCE_DIR}/${file} vulkan_includes REGEX "^#include <vulkan/")
      foreach(line IN LISTS vulkan_includes)
        string(APPEND violations "\n  ${file}: ${line} (Vulkan is reached only through host/backend)")
      endforeach()
    endif()
  endforeach()
endforeach()
if(violations)
  message(FATAL_ERROR "spectrace module layering: includes against the module graph (host/*/CMakeLists.txt):${violations}")
endif()
