# `hpsf sweep`'s frames axis and the methods of several filtered bounces (docs/guide/accuracy-sweeps.md): a grid of
# one and four frames over pt, hpsf, nhpsf and anhpsf. Each configuration of four frames reports its relMSE after
# every frame: the first is that of the same method's one-frame configuration (frame 0 traced and filtered alike),
# the last is its relMSE. Path tracing over frames is the mean of its frames' images, so four frames come out well
# below one. nhpsf traces short paths (fewer rays per pixel than pt's deep ones), anhpsf continues them across frames
# (more rays from the second frame on). Each configuration's frontier and path tracing's relMSE at equal time are
# taken among the configurations after as many frames. frames.png is drawn. An animated scene is measured frame by
# frame.
set(dir ${OUT}/sweep_frames_cli)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
execute_process(COMMAND ${HPSF} sweep cornell --grid "frames=1,4; method=pt,hpsf,nhpsf,anhpsf; temporal=ema:0.875"
                        --size 24x24 --seeds 2 --reference-spp 32 --cache ${dir}/cache --out ${dir}/sweep --json
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "hpsf sweep: exit ${code}\n${out}${err}")
endif()

# The configuration of `method` after `frames` frames, as JSON, in `result`.
function(config method frames result)
  string(JSON count LENGTH "${out}" configurations)
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON c GET "${out}" configurations ${i})
    string(JSON m GET "${c}" method)
    string(JSON f GET "${c}" frames)
    if(m STREQUAL method AND f EQUAL frames)
      set(${result} "${c}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  message(FATAL_ERROR "no configuration of ${method} after ${frames} frames:\n${out}")
endfunction()

foreach(method pt hpsf nhpsf anhpsf)
  config(${method} 1 one)
  config(${method} 4 four)
  string(JSON one_relmse GET "${one}" relmse)
  string(JSON four_relmse GET "${four}" relmse)
  string(JSON first GET "${four}" relmse_by_frame 0)
  string(JSON fourth GET "${four}" relmse_by_frame 3)
  string(JSON frames LENGTH "${four}" relmse_by_frame)
  if(NOT frames EQUAL 4 OR NOT first STREQUAL one_relmse OR NOT fourth STREQUAL four_relmse)
    message(FATAL_ERROR "${method}: after frame 1 ${first} (one frame: ${one_relmse}), after frame 4 ${fourth} "
                        "(the relMSE: ${four_relmse}), ${frames} frames reported")
  endif()
  string(JSON pt_at_equal_time_1 GET "${one}" pt_relmse_at_equal_time)
  string(JSON pt_at_equal_time GET "${four}" pt_relmse_at_equal_time)
  string(JSON rays_${method}_1 GET "${one}" rays_per_pixel)
  string(JSON rays_${method}_4 GET "${four}" rays_per_pixel)
  set(relmse_${method}_1 ${one_relmse})
  set(relmse_${method}_4 ${four_relmse})
  set(pt_at_equal_time_${method}_1 "${pt_at_equal_time_1}")
  set(pt_at_equal_time_${method}_4 "${pt_at_equal_time}")
endforeach()

# Path tracing's mean of four frames (a quarter of the variance); nhpsf's short paths; anhpsf's continued ones.
foreach(check "${relmse_pt_4} < 0.5 * ${relmse_pt_1}" "${rays_nhpsf_1} < ${rays_pt_1}"
              "${rays_anhpsf_4} > ${rays_nhpsf_4}")
  # CMake compares no floats with arithmetic: the check goes to a calculator that does.
  execute_process(COMMAND awk "BEGIN { exit !(${check}) }" RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "expected ${check}")
  endif()
endforeach()
# Path tracing's relMSE at equal time is that of pt after as many frames: after one, hpsf filters pt's own batch
# (traced once for both), so it takes longer and pt's is the value (after four frames pt's is also as fast and better,
# the answer if frontiers mixed frame counts). After four frames each traces its own sequence, so which is faster is
# the machine's noise: pt's after four frames, or none (null) where pt's traces happened to be slower.
if(NOT pt_at_equal_time_hpsf_1 STREQUAL relmse_pt_1)
  message(FATAL_ERROR "hpsf after 1 frame: pt's relMSE at equal time ${pt_at_equal_time_hpsf_1}, expected pt's after "
                      "1 frame, ${relmse_pt_1}")
endif()
if(NOT pt_at_equal_time_hpsf_4 STREQUAL relmse_pt_4 AND NOT pt_at_equal_time_hpsf_4 STREQUAL "")
  message(FATAL_ERROR "hpsf after 4 frames: pt's relMSE at equal time ${pt_at_equal_time_hpsf_4}, expected pt's "
                      "after 4 frames, ${relmse_pt_4}, or none")
endif()
execute_process(COMMAND oiiotool --info ${dir}/sweep/frames.png OUTPUT_VARIABLE plot)
if(NOT plot MATCHES "960 x +600, 3 channel")
  message(FATAL_ERROR "no plot of relMSE against frames of 960x600: ${plot}")
endif()
file(READ ${dir}/sweep/sweep.csv csv)
if(NOT csv MATCHES "^id,method,backend,spp,frames,temporal,")
  message(FATAL_ERROR "sweep.csv's header: ${csv}")
endif()
# An animated scene (the dolly's moving camera): each frame measured against its own converged image, one rendered per
# frame up to the longest sequence's last (three in the cache); a sequence's first frame is measured as the one-frame
# configuration is, against frame 0's.
execute_process(COMMAND ${HPSF} sweep ${SCENES}/cornell-dolly.json --grid "frames=1,3; method=pt,hpsf" --size 16x16
                        --seeds 2 --reference-spp 32 --cache ${dir}/animated-cache --out ${dir}/animated --json
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "hpsf sweep of an animated scene: exit ${code}\n${out}${err}")
endif()
file(GLOB converged ${dir}/animated-cache/*.exr)
list(LENGTH converged converged_count)
if(NOT converged_count EQUAL 3)
  message(FATAL_ERROR "an animated sweep of 3 frames renders 3 converged images, not ${converged_count}")
endif()
foreach(method pt hpsf)
  config(${method} 1 one)
  config(${method} 3 three)
  string(JSON one_relmse GET "${one}" relmse)
  string(JSON first GET "${three}" relmse_by_frame 0)
  if(NOT first STREQUAL one_relmse)
    message(FATAL_ERROR "${method} on a moving camera: after frame 1 ${first}, one frame ${one_relmse}")
  endif()
endforeach()
