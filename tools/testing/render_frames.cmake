# hpsf render --frames K: every backend traces and filters K frames through one table; --frame-out writes each
# frame, -o the last (the same file bytes as the last frame's); the JSON report lists the frames. The last frame
# of a sequence is not the frame filtered alone (its table holds the frames before it). With --eviction, each
# frame's entry reports its eviction, the same count on every backend, and with --temporal ema:0.5 besides every
# backend blends to the reference's pixels. Bad patterns and modes exit 3 and write nothing.
set(dir ${OUT}/frames)
file(REMOVE_RECURSE ${dir})
set(common render ${SCENE} --size 24x24 --spp 2 --frames 3 --capacity 16384 --json)
foreach(backend reference emulated vulkan)
  execute_process(COMMAND ${HPSF} ${common} --backend ${backend} --frame-out ${dir}/${backend}-{frame}.exr
                          -o ${dir}/${backend}-last.exr
                  RESULT_VARIABLE code OUTPUT_VARIABLE report ERROR_VARIABLE errors)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${backend}: exit ${code}\n${errors}")
  endif()
  foreach(frame 0000 0001 0002)
    foreach(extension exr png)
      if(NOT EXISTS ${dir}/${backend}-${frame}.${extension})
        message(FATAL_ERROR "${backend}: no ${backend}-${frame}.${extension}")
      endif()
    endforeach()
  endforeach()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${dir}/${backend}-last.exr ${dir}/${backend}-0002.exr
                  RESULT_VARIABLE differ)
  if(NOT differ EQUAL 0)
    message(FATAL_ERROR "${backend}: -o differs from the last frame's file")
  endif()
  string(JSON frames LENGTH "${report}" frames)
  string(JSON last GET "${report}" trace frame)
  if(NOT frames EQUAL 3 OR NOT last EQUAL 2)
    message(FATAL_ERROR "${backend}: the report lists ${frames} frames, the last ${last}")
  endif()
  # The same frame alone: another image, since the sequence's table also holds frames 0 and 1.
  execute_process(COMMAND ${HPSF} render ${SCENE} --size 24x24 --spp 2 --capacity 16384 --frame 2 --backend ${backend} -o ${dir}/${backend}-alone.exr
                  RESULT_VARIABLE code)
  execute_process(COMMAND idiff -fail 0 -warn 0 ${dir}/${backend}-alone.exr ${dir}/${backend}-last.exr
                  RESULT_VARIABLE same OUTPUT_QUIET ERROR_QUIET)
  if(NOT code EQUAL 0 OR same EQUAL 0)
    message(FATAL_ERROR "${backend}: frame 2 of the sequence has the pixels of frame 2 alone (exit ${code})")
  endif()
endforeach()
# The three backends' last frames: the same pixels (fixed64, an uncrowded table).
foreach(backend emulated vulkan)
  execute_process(COMMAND idiff -fail 0 -warn 0 ${dir}/reference-last.exr ${dir}/${backend}-last.exr
                  RESULT_VARIABLE differ OUTPUT_VARIABLE idiff_report)
  if(NOT differ EQUAL 0)
    message(FATAL_ERROR "${backend}'s last frame differs from the reference's:\n${idiff_report}")
  endif()
endforeach()

# --eviction strict --temporal ema:0.5, in one run per backend: each frame's entry gives its eviction and every
# backend evicts the same number of cells; every backend blends to the reference's pixels, which are not
# integration's; the report's config names the mode.
foreach(backend reference emulated vulkan)
  execute_process(COMMAND ${HPSF} ${common} --backend ${backend} --eviction strict --temporal ema:0.5
                          -o ${dir}/${backend}-strict-ema.exr
                  RESULT_VARIABLE code OUTPUT_VARIABLE report ERROR_VARIABLE errors)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${backend} --eviction strict --temporal ema:0.5: exit ${code}\n${errors}")
  endif()
  string(JSON temporal GET "${report}" config temporal)
  if(NOT temporal STREQUAL "ema:0.5")
    message(FATAL_ERROR "${backend}: the report's config says temporal '${temporal}'")
  endif()
  set(counts)
  foreach(frame 0 1 2)
    if(backend STREQUAL "reference")
      string(JSON evicted GET "${report}" frames ${frame} eviction cells_evicted)
    else()
      string(JSON evicted GET "${report}" frames ${frame} eviction evicted)
      string(JSON seconds GET "${report}" frames ${frame} eviction eviction_s)
    endif()
    list(APPEND counts ${evicted})
  endforeach()
  if(backend STREQUAL "reference")
    set(reference_counts "${counts}")
    if(counts STREQUAL "0;0;0")
      message(FATAL_ERROR "the animated scene evicted nothing over 3 frames")
    endif()
  elseif(NOT counts STREQUAL reference_counts)
    message(FATAL_ERROR "${backend} evicted ${counts} cells per frame, the reference ${reference_counts}")
  endif()
endforeach()
foreach(backend emulated vulkan)
  execute_process(COMMAND idiff -fail 0 -warn 0 ${dir}/reference-strict-ema.exr ${dir}/${backend}-strict-ema.exr
                  RESULT_VARIABLE differ OUTPUT_VARIABLE idiff_report)
  if(NOT differ EQUAL 0)
    message(FATAL_ERROR "${backend}'s strict, ema:0.5 frame differs from the reference's:\n${idiff_report}")
  endif()
endforeach()
execute_process(COMMAND idiff -fail 0 -warn 0 ${dir}/reference-strict-ema.exr ${dir}/reference-last.exr
                RESULT_VARIABLE same OUTPUT_QUIET ERROR_QUIET)
if(same EQUAL 0)
  message(FATAL_ERROR "strict, ema:0.5 gives the pixels of no eviction and integration")
endif()
execute_process(COMMAND ${HPSF} ${common} --temporal ema:2 -o ${dir}/bad-ema.exr
                RESULT_VARIABLE code ERROR_VARIABLE errors)
if(NOT code EQUAL 3 OR NOT errors MATCHES "--temporal")
  message(FATAL_ERROR "--temporal ema:2: exit ${code}, '${errors}'")
endif()

foreach(bad "${dir}/bad.exr" "${dir}/bad-{frame}-{frame}.exr" "${dir}/bad-{frame}.png")
  execute_process(COMMAND ${HPSF} ${common} --frame-out ${bad} -o ${dir}/bad-last.exr
                  RESULT_VARIABLE code ERROR_VARIABLE errors)
  if(NOT code EQUAL 3 OR NOT errors MATCHES "--frame-out")
    message(FATAL_ERROR "--frame-out ${bad}: exit ${code}, '${errors}'")
  endif()
endforeach()
file(GLOB left ${dir}/bad*)
if(left)
  message(FATAL_ERROR "bad input left files behind: ${left}")
endif()
