# hpsf's own table as a declaration renders the same bits as the defaults: the same EXR, byte for byte, on the
# reference and on the emulator.
foreach(backend reference emulated)
  set(common render cornell --size 48x32 --spp 2 --seed 3 --backend ${backend})
  file(REMOVE ${OUT}/table_default.exr ${OUT}/table_declared.exr)
  execute_process(COMMAND ${HPSF} ${common} -o ${OUT}/table_default.exr RESULT_VARIABLE a)
  execute_process(COMMAND ${HPSF} ${common} --table ${TABLES}/hpsf.json -o ${OUT}/table_declared.exr RESULT_VARIABLE b)
  if(NOT a EQUAL 0 OR NOT b EQUAL 0)
    message(FATAL_ERROR "${backend}: a render failed: ${a} ${b}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/table_default.exr ${OUT}/table_declared.exr
    RESULT_VARIABLE differ)
  if(NOT differ EQUAL 0)
    message(FATAL_ERROR "${backend}: hpsf.json renders other bits than the defaults")
  endif()
endforeach()
