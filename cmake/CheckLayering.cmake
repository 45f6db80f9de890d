# cmake -DSOURCE_DIR=<repo> -DGRAPH=<module_graph.cmake> -P CheckLayering.cmake
# (GRAPH sets MODULES and each <module>_DEPS; host/CMakeLists.txt writes it.)
# Fails when a file of host/<module>/ (tests excepted) includes a header of
# another host module that <module> does not link, directly or through its
# dependencies: the module graph stays acyclic and one-way, and a new
# back-arrow stops the build instead of creeping in.
cmake_minimum_required(VERSION 3.25)
include(${GRAPH})

# The transitive closure of a module's dependencies.
function(closure module out)
  set(seen)
  set(queue ${${module}_DEPS})
  while(queue)
    list(POP_FRONT queue next)
    if(NOT next IN_LIST seen)
      list(APPEND seen ${next})
      list(APPEND queue ${${next}_DEPS})
    endif()
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

set(violations "")
foreach(module IN LISTS MODULES)
  closure(${module} allowed)
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
  endforeach()
endforeach()
if(violations)
  message(FATAL_ERROR "spectrace module layering: includes against the module graph (host/CMakeLists.txt):${violations}")
endif()
