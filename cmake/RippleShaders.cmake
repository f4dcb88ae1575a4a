# GLSL compute shaders -> SPIR-V (glslc, its depfile naming the generated header, so that editing an
# included file rebuilds the shaders that include it and nothing else) -> validated by spirv-val ->
# embedded as uint32_t arrays in generated headers. Nothing is loaded from disk at run time.
find_program(GLSLC glslc REQUIRED)
find_program(SPIRV_VAL spirv-val REQUIRED)

# ripple_add_shaders(<interface-target> <file.comp>...): headers land in
# ${CMAKE_BINARY_DIR}/generated/shaders/<name>.spv.h, each defining ripple::shaders::<name>. Includes are
# looked up beside the including file, in the calling folder, then in shaders/ (shared/*.h and the .glsl
# pieces that kernels outside shaders/, such as bench/kernels, share with the renderer).
function(ripple_add_shaders target)
  set(out_dir "${CMAKE_BINARY_DIR}/generated/shaders")
  file(MAKE_DIRECTORY "${out_dir}")
  set(headers "")
  foreach(source IN LISTS ARGN)
    get_filename_component(name "${source}" NAME_WE)
    set(abs_source "${CMAKE_CURRENT_SOURCE_DIR}/${source}")
    set(spv "${out_dir}/${name}.spv")
    set(header "${out_dir}/${name}.spv.h")
    add_custom_command(
      OUTPUT "${header}"
      COMMAND ${GLSLC} --target-env=vulkan1.2 -O -Werror -I "${CMAKE_CURRENT_SOURCE_DIR}"
              -I "${PROJECT_SOURCE_DIR}/shaders" -I "${NANOVDB_INCLUDE_DIR}"
              -MD -MF "${spv}.d" -MT "${header}" -o "${spv}" "${abs_source}"
      COMMAND ${SPIRV_VAL} --target-env vulkan1.2 "${spv}"
      COMMAND ${CMAKE_COMMAND} -DINPUT=${spv} -DOUTPUT=${header} -DNAME=${name}
              -P "${PROJECT_SOURCE_DIR}/cmake/SpirvToHeader.cmake"
      DEPENDS "${abs_source}" "${PROJECT_SOURCE_DIR}/cmake/SpirvToHeader.cmake"
      DEPFILE "${spv}.d"
      COMMENT "GLSL ${source} -> SPIR-V (validated) -> ${name}.spv.h"
      VERBATIM)
    list(APPEND headers "${header}")
  endforeach()
  add_custom_target(${target}_compile DEPENDS ${headers})
  add_library(${target} INTERFACE)
  add_dependencies(${target} ${target}_compile)
  target_include_directories(${target} INTERFACE "${CMAKE_BINARY_DIR}/generated")
endfunction()
