# Run as a script after glslang (cmake/Shaders.cmake): glslang keeps one execution mode per mode, so a shader that
# declares round-to-nearest-even and signed-zero/Inf/NaN preservation for 32-bit floats (float_controls.glsl) and for
# 64-bit ones (float_controls_fp64.glsl) comes out with the 64-bit ones alone, and its float32 arithmetic (a key in
# the neighbourhood search and the transport, float sums) may round or flush as the driver likes. This puts the
# 32-bit modes back beside the 64-bit ones, then, with HEADER and NAME, writes the module as a C array header
# `NAME[]`, as glslang's --vn would.
# -DSPV=file.spv -DSPIRV_DIS=... -DSPIRV_AS=... -DTARGET_ENV=vulkan1.2 [-DHEADER=file.h -DNAME=name_spv]
execute_process(COMMAND ${SPIRV_DIS} --raw-id ${SPV} OUTPUT_VARIABLE text RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "${SPV}: spirv-dis failed")
endif()
foreach(mode RoundingModeRTE SignedZeroInfNanPreserve)
  if(text MATCHES " ${mode} 32\n")
    continue()
  endif()
  if(text MATCHES "OpExecutionMode (%[0-9]+) ${mode} 64\n")
    set(entry ${CMAKE_MATCH_1})
    string(REPLACE "OpExecutionMode ${entry} ${mode} 64\n"
                   "OpExecutionMode ${entry} ${mode} 64\nOpExecutionMode ${entry} ${mode} 32\n" text "${text}")
    set(patched TRUE)
  endif()
endforeach()
if(patched)
  file(WRITE ${SPV}.txt "${text}")
  execute_process(COMMAND ${SPIRV_AS} --preserve-numeric-ids --target-env ${TARGET_ENV} -o ${SPV} ${SPV}.txt
                  RESULT_VARIABLE failed)
  file(REMOVE ${SPV}.txt)
  if(failed)
    message(FATAL_ERROR "${SPV}: spirv-as failed on the module with its 32-bit float controls restored")
  endif()
endif()
if(HEADER)
  file(READ ${SPV} hex HEX)
  # Little-endian words: each 8 hex digits reversed byte by byte.
  string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1," words "${hex}")
  set(word "0x........,")
  string(REGEX REPLACE "(${word}${word}${word}${word}${word}${word}${word}${word})" "\\1\n  " words "${words}")
  file(WRITE ${HEADER} "#pragma once\n// ${NAME}: generated from ${SPV} by cmake/RestoreFloatControls.cmake\n"
                       "const uint32_t ${NAME}[] = {\n  ${words}\n};\n")
endif()
