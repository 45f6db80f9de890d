# spectrace_add_shaders(TARGET <lib> HEADER <name.h> SHADERS <path/file.comp> ...)
# Compiles each compute shader with glslang at build time (never committed
# .spv files) and embeds the SPIR-V in <lib> as spectrace::embedded::spv_<name>().
function(spectrace_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET;HEADER" "SHADERS" ${ARGN})
  set(spv_dir ${CMAKE_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${spv_dir})
  set(embed_list)
  foreach(src IN LISTS ARG_SHADERS)
    get_filename_component(name ${src} NAME_WE)
    set(spv ${spv_dir}/${name}.spv)
    add_custom_command(OUTPUT ${spv}
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.2 -V
              --depfile ${spv}.d -o ${spv} ${src}
      DEPENDS ${src}
      DEPFILE ${spv}.d
      COMMENT "glslang ${src}"
      VERBATIM)
    list(APPEND embed_list "spv_${name}=${spv}")
  endforeach()
  spectrace_embed(TARGET ${ARG_TARGET} HEADER ${ARG_HEADER} FILES ${embed_list})
endfunction()
