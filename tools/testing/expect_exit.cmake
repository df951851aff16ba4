# ctest driver: runs COMMAND (a ;-list) with optional ENV (a ;-list of NAME=VALUE), and requires exit code
# EXPECT_CODE and, when given, stderr or stdout matching EXPECT_MESSAGE.
set(env_prefix)
if(ENV)
  set(env_prefix ${CMAKE_COMMAND} -E env ${ENV})
endif()
execute_process(COMMAND ${env_prefix} ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit ${code}\nstdout: ${out}\nstderr: ${err}")
if(NOT code EQUAL EXPECT_CODE)
  message(FATAL_ERROR "exited ${code}, expected ${EXPECT_CODE}")
endif()
if(EXPECT_MESSAGE AND NOT "${out}${err}" MATCHES "${EXPECT_MESSAGE}")
  message(FATAL_ERROR "output does not match '${EXPECT_MESSAGE}'")
endif()
