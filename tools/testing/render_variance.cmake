# `hpsf render --variance` and `hpsf replay --variance` write the pixel variance into the EXR, by channel name after
# R, G, B (each pixel's and each 8x8 tile's, EXR's alphabetical order), with the image mean's variance, the samples
# per pixel and the tile size as metadata; a statistical diff of an image below 4 spp is refused naming the minimum;
# without the flag the EXR keeps its three channels. Read back with OpenImageIO's iinfo, as any other tool would see the file.
set(common --size 16x16 --spp 4 --seed 3)
file(REMOVE ${OUT}/variance.exr ${OUT}/variance_replay.exr ${OUT}/variance_none.exr)
execute_process(COMMAND ${HPSF} render cornell ${common} --variance -o ${OUT}/variance.exr
  --dump-records ${OUT}/variance.hpsfv RESULT_VARIABLE a OUTPUT_VARIABLE report)
execute_process(COMMAND ${HPSF} replay ${OUT}/variance.hpsfv --seed 3 --variance --no-filter
  -o ${OUT}/variance_replay.exr RESULT_VARIABLE b)
execute_process(COMMAND ${HPSF} render cornell ${common} -o ${OUT}/variance_none.exr RESULT_VARIABLE c)
if(NOT a EQUAL 0 OR NOT b EQUAL 0 OR NOT c EQUAL 0)
  message(FATAL_ERROR "a render failed: ${a} ${b} ${c}")
endif()
if(NOT report MATCHES "variance of the image mean: [0-9]")
  message(FATAL_ERROR "the report does not give the image mean's variance:\n${report}")
endif()
foreach(file variance variance_replay)
  execute_process(COMMAND iinfo -v ${OUT}/${file}.exr OUTPUT_VARIABLE info RESULT_VARIABLE code)
  message("${file}.exr:\n${info}")
  foreach(expected "16 x   16, 9 channel, float"
                   "channel list: R, G, B, tile_variance.R, tile_variance.G, tile_variance.B, variance.R, variance.G, variance.B"
                   "hpsf:mean_variance: \"[0-9.e+-]+ [0-9.e+-]+ [0-9.e+-]+\"" "hpsf:spp: \"4\"" "hpsf:variance_tile: \"8\"")
    if(NOT code EQUAL 0 OR NOT info MATCHES "${expected}")
      message(FATAL_ERROR "${file}.exr does not have '${expected}'")
    endif()
  endforeach()
endforeach()
execute_process(COMMAND iinfo -v ${OUT}/variance_none.exr OUTPUT_VARIABLE info)
if(NOT info MATCHES "3 channel, float" OR info MATCHES "variance\\.R|hpsf:mean_variance|hpsf:spp|hpsf:variance_tile")
  message(FATAL_ERROR "without --variance the EXR must keep R, G, B alone:\n${info}")
endif()

# diff --statistical refuses an image of fewer than 4 spp (its measured false alarms exceed alpha there).
execute_process(COMMAND ${HPSF} render cornell --size 16x16 --spp 2 --seed 3 --variance -o ${OUT}/variance_2spp.exr
  RESULT_VARIABLE code)
execute_process(COMMAND ${HPSF} diff --statistical ${OUT}/variance.exr ${OUT}/variance_2spp.exr
  RESULT_VARIABLE code ERROR_VARIABLE err)
if(NOT code EQUAL 3 OR NOT err MATCHES "variance_2spp.exr: 2 samples per pixel; .* from 4 spp on \\(render it with --spp 4 or more\\)")
  message(FATAL_ERROR "a 2-spp image must be refused, exit 3 naming the minimum: exit ${code}: ${err}")
endif()
