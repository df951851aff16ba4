# ctest driver for one spirv_lint case: compile SHADER, lint it, and require exit code EXPECT_CODE and, for a
# rejected shader, the message EXPECT_MESSAGE.
execute_process(COMMAND ${GLSLANG} -V --quiet --target-env vulkan1.2 -o ${OUT} ${SHADER} RESULT_VARIABLE compiled)
if(NOT compiled EQUAL 0)
  message(FATAL_ERROR "${SHADER} did not compile")
endif()
execute_process(COMMAND ${LINT} ${OUT} RESULT_VARIABLE code ERROR_VARIABLE stderr)
message("${stderr}")
if(NOT code EQUAL EXPECT_CODE)
  message(FATAL_ERROR "spirv_lint exited ${code}, expected ${EXPECT_CODE}")
endif()
if(EXPECT_MESSAGE AND NOT stderr MATCHES "${EXPECT_MESSAGE}")
  message(FATAL_ERROR "spirv_lint did not report '${EXPECT_MESSAGE}'")
endif()
