# vitrum_compile_shaders(OUT_VAR SOURCES a.comp b.comp INCLUDE_DIR dir)
#
# Compiles each GLSL compute shader with glslangValidator for Vulkan 1.2 into a C++ header that
# holds the SPIR-V as `uint32_t <name>_spv[]` (name: the file name without extension), in
# ${CMAKE_CURRENT_BINARY_DIR}/shaders/<name>.spv.h. glslangValidator writes a depfile, so editing
# an included file (shaders/*.glsl, shaders/shared/*.h) rebuilds the shaders that include it.
function(vitrum_compile_shaders OUT_VAR)
  cmake_parse_arguments(ARG "" "INCLUDE_DIR" "SOURCES" ${ARGN})
  set(headers)
  file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/shaders)
  foreach(source IN LISTS ARG_SOURCES)
    get_filename_component(name ${source} NAME_WE)
    set(header ${CMAKE_CURRENT_BINARY_DIR}/shaders/${name}.spv.h)
    set(depfile ${CMAKE_CURRENT_BINARY_DIR}/shaders/${name}.spv.d)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.2 -I${ARG_INCLUDE_DIR}
              --vn ${name}_spv --depfile ${depfile} -o ${header}
              ${CMAKE_CURRENT_SOURCE_DIR}/${source}
      MAIN_DEPENDENCY ${CMAKE_CURRENT_SOURCE_DIR}/${source}
      DEPFILE ${depfile}
      COMMENT "Compiling shader ${source}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  set(${OUT_VAR} ${headers} PARENT_SCOPE)
endfunction()
