# spectrace_embed(TARGET <lib> HEADER <name.h> FILES <sym>=<path> ...)
# Turns each file into a byte array compiled into <lib>, reachable as
# `std::span<const unsigned char> spectrace::embedded::<sym>()` declared in the
# generated header. The bytes are 4-byte aligned so SPIR-V can be read as words.
set(SPECTRACE_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/embed_file.cmake)

function(spectrace_embed)
  cmake_parse_arguments(ARG "" "TARGET;HEADER" "FILES" ${ARGN})
  set(gen_dir ${CMAKE_BINARY_DIR}/generated)
  set(header ${gen_dir}/${ARG_HEADER})
  set(decls "#pragma once\n#include <span>\nnamespace spectrace::embedded {\n")
  foreach(entry IN LISTS ARG_FILES)
    string(REPLACE "=" ";" parts "${entry}")
    list(GET parts 0 sym)
    list(GET parts 1 path)
    set(out ${gen_dir}/embedded_${sym}.cpp)
    add_custom_command(OUTPUT ${out}
      COMMAND ${CMAKE_COMMAND} -DINPUT=${path} -DOUTPUT=${out} -DSYMBOL=${sym} -P ${SPECTRACE_EMBED_SCRIPT}
      DEPENDS ${path} ${SPECTRACE_EMBED_SCRIPT}
      COMMENT "Embedding ${sym}"
      VERBATIM)
    target_sources(${ARG_TARGET} PRIVATE ${out})
    string(APPEND decls "std::span<const unsigned char> ${sym}();\n")
  endforeach()
  string(APPEND decls "}  // namespace spectrace::embedded\n")
  file(GENERATE OUTPUT ${header} CONTENT "${decls}")
endfunction()
