# Effect planning in hpsf render (core/effect_plan.h): on the static Cornell box over 3 frames the scene is built
# once (scene_s zero after the first frame) and stale:3 evicts nothing, so the eviction pass is skipped (its timer
# zero) while the asked-for ema blend runs on frames 1 and 2; the JSON report lists each effect, whether it ran and
# why. Forcing the skipped ones gives the same pixels, with the build and the pass timed on every frame. The
# animated box rebuilds every frame. The neighbourhood search's pass on Vulkan forced over every pixel gives the
# pixels of the pass over those below the threshold. A name that is not an effect, or forcing a pass the options do
# not ask for, exits 3.
set(dir ${OUT}/effects)
file(REMOVE_RECURSE ${dir})
set(common render cornell --size 24x24 --spp 2 --frames 3 --capacity 16384 --backend emulated --json
    --eviction stale:3 --temporal ema:0.5)

function(effect report name field out)
  string(JSON count LENGTH "${report}" effects)
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON effect GET "${report}" effects ${i} effect)
    if(effect STREQUAL name)
      string(JSON value GET "${report}" effects ${i} ${field})
      set(${out} "${value}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  message(FATAL_ERROR "the report lists no effect ${name}")
endfunction()

function(render label)
  execute_process(COMMAND ${HPSF} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE report ERROR_VARIABLE errors)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${label}: exit ${code}\n${errors}")
  endif()
  set(report "${report}" PARENT_SCOPE)
endfunction()

render(planned ${common} -o ${dir}/planned.exr)
effect("${report}" animation ran ran)
effect("${report}" eviction ran evicted)
effect("${report}" eviction reason why)
effect("${report}" temporal frames_run blended)
if(ran OR evicted OR NOT blended EQUAL 2)
  message(FATAL_ERROR "planned: animation ran ${ran}, eviction ran ${evicted}, temporal on ${blended} frames")
endif()
if(NOT why MATCHES "before frame 3")
  message(FATAL_ERROR "planned: the eviction's reason is '${why}'")
endif()
foreach(frame 1 2)
  string(JSON scene_s GET "${report}" frames ${frame} scene_s)
  string(JSON eviction_s GET "${report}" frames ${frame} eviction eviction_s)
  if(NOT scene_s EQUAL 0 OR NOT eviction_s EQUAL 0)
    message(FATAL_ERROR
            "planned frame ${frame}: scene_s ${scene_s}, eviction_s ${eviction_s}: a skipped effect took time")
  endif()
endforeach()

render(forced ${common} --force-effect animation --force-effect eviction -o ${dir}/forced.exr)
effect("${report}" animation frames_run built)
effect("${report}" eviction frames_run evicted)
effect("${report}" eviction forced forced)
if(NOT built EQUAL 3 OR NOT evicted EQUAL 3 OR NOT forced)
  message(FATAL_ERROR "forced: built on ${built} frames, evicted on ${evicted}, forced ${forced}")
endif()
foreach(frame 1 2)
  string(JSON scene_s GET "${report}" frames ${frame} scene_s)
  string(JSON eviction_s GET "${report}" frames ${frame} eviction eviction_s)
  if(scene_s EQUAL 0 OR eviction_s EQUAL 0)
    message(FATAL_ERROR
            "forced frame ${frame}: scene_s ${scene_s}, eviction_s ${eviction_s}: a forced effect did not run")
  endif()
endforeach()
execute_process(COMMAND idiff -fail 0 -warn 0 ${dir}/planned.exr ${dir}/forced.exr
                RESULT_VARIABLE differ OUTPUT_VARIABLE idiff_report)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "forcing the skipped effects changed the pixels:\n${idiff_report}")
endif()

# The search pass on Vulkan, planned (the pixels below the threshold) and forced (every pixel): the same pixels.
set(search render cornell --size 24x24 --spp 2 --capacity 16384 --backend vulkan --json --neighbour-search on
    --min-count 4)
render(searched ${search} -o ${dir}/searched.exr)
effect("${report}" neighbour-search frames_run searched)
render(search_forced ${search} --force-effect neighbour-search -o ${dir}/search-forced.exr)
effect("${report}" neighbour-search forced search_forced)
if(NOT searched EQUAL 1 OR NOT search_forced)
  message(FATAL_ERROR "the search ran on ${searched} of 1 frame, forced: ${search_forced}")
endif()
execute_process(COMMAND idiff -fail 0 -warn 0 ${dir}/searched.exr ${dir}/search-forced.exr
                RESULT_VARIABLE differ OUTPUT_VARIABLE idiff_report)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "forcing the search pass changed the pixels:\n${idiff_report}")
endif()

render(animated render ${SCENE} --size 24x24 --spp 1 --frames 3 --capacity 16384 --json -o ${dir}/animated.exr)
effect("${report}" animation frames_run built)
if(NOT built EQUAL 3)
  message(FATAL_ERROR "the animated scene was built on ${built} of 3 frames")
endif()

foreach(bad "glossy" "level-seed" "neighbour-search")
  execute_process(COMMAND ${HPSF} ${common} --force-effect ${bad} -o ${dir}/bad.exr
                  RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE errors)
  if(NOT code EQUAL 3 OR NOT errors MATCHES "--force-effect" OR EXISTS ${dir}/bad.exr)
    message(FATAL_ERROR "--force-effect ${bad}: exit ${code}, '${errors}'")
  endif()
endforeach()
