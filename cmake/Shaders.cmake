# Compiles a GLSL compute shader to SPIR-V at build time, validates it, optionally lints it for the key path
# (tools/spirv_lint: no division or transcendental, NoContraction everywhere, float controls declared), and
# embeds it as a C array header `<name>_spv.h` defining `uint32_t <name>_spv[]`.
set(HPSF_SHADER_TARGET_ENV vulkan1.2)
# OFF only to show that the key-identity tests catch, on their own, what the lint would have stopped.
option(HPSF_LINT_KEY_SHADERS "Fail the build when a key-path shader uses inexact arithmetic" ON)
file(GLOB HPSF_SHARED_SOURCES CONFIGURE_DEPENDS
     ${PROJECT_SOURCE_DIR}/core/shared/*.h ${PROJECT_SOURCE_DIR}/vulkan/shaders/*.glsl)

set(HPSF_RESTORE_FLOAT_CONTROLS ${CMAKE_CURRENT_LIST_DIR}/RestoreFloatControls.cmake)
function(hpsf_add_shader target source)
  cmake_parse_arguments(ARG "KEY_PATH" "" "" ${ARGN})
  get_filename_component(name ${source} NAME_WE)
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/shaders)
  set(spv ${out_dir}/${name}.spv)
  set(header ${out_dir}/${name}_spv.h)
  set(lint_command)
  if(ARG_KEY_PATH AND HPSF_LINT_KEY_SHADERS)
    set(lint_command COMMAND $<TARGET_FILE:spirv_lint> ${spv})
  endif()
  add_custom_command(
    OUTPUT ${spv} ${header}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir}
    COMMAND ${GLSLANG_VALIDATOR} -V --quiet --target-env ${HPSF_SHADER_TARGET_ENV} -o ${spv} ${source}
    COMMAND ${CMAKE_COMMAND} -DSPV=${spv} -DSPIRV_DIS=${SPIRV_DIS} -DSPIRV_AS=${SPIRV_AS}
            -DTARGET_ENV=${HPSF_SHADER_TARGET_ENV} -DHEADER=${header} -DNAME=${name}_spv
            -P ${HPSF_RESTORE_FLOAT_CONTROLS}
    COMMAND ${SPIRV_VAL} --target-env ${HPSF_SHADER_TARGET_ENV} ${spv}
    ${lint_command}
    DEPENDS ${source} ${HPSF_SHARED_SOURCES} ${HPSF_RESTORE_FLOAT_CONTROLS} $<$<BOOL:${ARG_KEY_PATH}>:spirv_lint>
    COMMENT "Compiling, validating and linting ${name}.comp"
    VERBATIM)
  target_sources(${target} PRIVATE ${header})
  target_include_directories(${target} PRIVATE ${out_dir})
endfunction()
