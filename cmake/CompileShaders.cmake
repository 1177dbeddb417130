# vitrum_compile_shaders(OUT_VAR SOURCES a.comp b.comp [VARIANTS name=source:DEFINE ...] INCLUDE_DIR dir)
#
# Compiles each GLSL compute shader with glslangValidator for Vulkan 1.2, passes the SPIR-V
# through spirv-opt (cmake/OptimizeSpirv.cmake says which passes and why) and writes it into a
# C++ header that holds it as `uint32_t <name>_spv[]` (name: the file name without extension), in
# ${CMAKE_CURRENT_BINARY_DIR}/shaders/<name>.spv.h. A variant compiles `source` again with
# DEFINE set, as <name>.spv.h. glslangValidator writes a depfile, so editing an included file
# (shaders/*.glsl, shaders/shared/*.h) rebuilds the shaders that include it.
set(_VITRUM_OPTIMIZE_SPIRV ${CMAKE_CURRENT_LIST_DIR}/OptimizeSpirv.cmake)

function(_vitrum_compile_shader name source include_dir defines header_var)
  set(spirv ${CMAKE_CURRENT_BINARY_DIR}/shaders/${name}.spv)
  set(header ${spirv}.h)
  set(depfile ${CMAKE_CURRENT_BINARY_DIR}/shaders/${name}.spv.d)
  set(define_flags)
  foreach(define IN LISTS defines)
    list(APPEND define_flags -D${define})
  endforeach()
  add_custom_command(
    OUTPUT ${spirv} ${header}
    COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.2 -I${include_dir} ${define_flags}
            --depfile ${depfile} -o ${spirv} ${CMAKE_CURRENT_SOURCE_DIR}/${source}
    COMMAND ${CMAKE_COMMAND} -DSPIRV_OPT=${SPIRV_OPT} -DSPIRV_VAL=${SPIRV_VAL} -DINPUT=${spirv}
            -DOUTPUT=${header} -DVARIABLE=${name}_spv -P ${_VITRUM_OPTIMIZE_SPIRV}
    MAIN_DEPENDENCY ${CMAKE_CURRENT_SOURCE_DIR}/${source}
    DEPENDS ${_VITRUM_OPTIMIZE_SPIRV}
    DEPFILE ${depfile}
    COMMENT "Compiling shader ${name}"
    VERBATIM)
  set(${header_var} ${header} PARENT_SCOPE)
endfunction()

function(vitrum_compile_shaders OUT_VAR)
  cmake_parse_arguments(ARG "" "INCLUDE_DIR" "SOURCES;VARIANTS" ${ARGN})
  set(headers)
  file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/shaders)
  foreach(source IN LISTS ARG_SOURCES)
    get_filename_component(name ${source} NAME_WE)
    _vitrum_compile_shader(${name} ${source} ${ARG_INCLUDE_DIR} "" header)
    list(APPEND headers ${header})
  endforeach()
  foreach(variant IN LISTS ARG_VARIANTS)
    if(NOT variant MATCHES "^([A-Za-z0-9_]+)=([^:]+):([A-Za-z0-9_]+)$")
      message(FATAL_ERROR "shader variant '${variant}' is not name=source:DEFINE")
    endif()
    _vitrum_compile_shader(${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ${ARG_INCLUDE_DIR} ${CMAKE_MATCH_3} header)
    list(APPEND headers ${header})
  endforeach()
  set(${OUT_VAR} ${headers} PARENT_SCOPE)
endfunction()
