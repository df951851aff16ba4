# Included by the command-line test drivers: hpsf_run(EXPECTED_CODE ARGS...) runs ${HPSF} ARGS in ${dir}, fails the
# test unless it exits EXPECTED_CODE, and leaves its stdout in `out` and its stderr in `err`.
function(hpsf_run expected_code)
  execute_process(COMMAND ${HPSF} ${ARGN} WORKING_DIRECTORY ${dir}
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "hpsf ${ARGN}: exit ${code}, expected ${expected_code}\n${out}${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()
