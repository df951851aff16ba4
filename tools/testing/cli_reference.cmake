# docs/reference/cli.md against what cli_reference writes from the command line's definitions.
# -DGENERATOR=<cli_reference> -DCOMMITTED=<docs/reference/cli.md> -DOUT=<scratch file>
execute_process(COMMAND ${GENERATOR} ${OUT} RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${GENERATOR} failed: ${code}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${COMMITTED} RESULT_VARIABLE differs)
if(differs)
  execute_process(COMMAND diff -u ${COMMITTED} ${OUT} OUTPUT_VARIABLE difference)
  message(FATAL_ERROR "${COMMITTED} has drifted from the command line; rewrite it with `cmake --build --preset "
    "default --target cli-reference`:\n${difference}")
endif()
