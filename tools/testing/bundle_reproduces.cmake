# Included by the ctest drivers that leave a repro bundle: the bundle, copied to a fresh folder as a CI artifact is
# downloaded elsewhere, and its reproduce.sh run from another folder with hpsf named by $HPSF (HPSF must be set),
# must fail again (exit 2) without a version warning and write reproduced.json equal, value for value, to the
# bundle's report.json.
function(hpsf_expect_bundle_reproduces bundle)
  foreach(file records.hpsfv report.json reproduce.sh)
    if(NOT EXISTS ${bundle}/${file})
      message(FATAL_ERROR "the repro bundle lacks ${file}")
    endif()
  endforeach()
  string(RANDOM LENGTH 8 fresh)
  set(moved ${bundle}-moved-${fresh})
  file(COPY ${bundle}/ DESTINATION ${moved})
  execute_process(COMMAND ${CMAKE_COMMAND} -E env HPSF=${HPSF} sh ${moved}/reproduce.sh WORKING_DIRECTORY /
                  RESULT_VARIABLE again ERROR_VARIABLE said)
  if(NOT again EQUAL 2)
    message(FATAL_ERROR "reproduce.sh of the moved bundle exited ${again}, expected 2:\n${said}")
  endif()
  if(said MATCHES "warning")
    message(FATAL_ERROR "reproduce.sh warned though the same hpsf runs it:\n${said}")
  endif()
  file(READ ${moved}/report.json first)
  file(READ ${moved}/reproduced.json second)
  string(JSON same EQUAL "${first}" "${second}")
  if(NOT same)
    message(FATAL_ERROR "the reproduced report differs from the original")
  endif()
  file(REMOVE_RECURSE ${moved})
endfunction()
