# `hpsf sweep`'s hashcache method (docs/guide/accuracy-sweeps.md): the HashCache over one and four frames on every
# backend. Each configuration is built once (a static scene), reports its fill and its relMSE after every frame, and
# writes its image beside its result. On cornell-animated,
# whose cube moves every frame, a sequence of three frames builds three times; on the dolly (only the camera moves),
# once. A HashCache of packed-decimal sums is bad input naming --grid, before anything is written.
set(dir ${OUT}/sweep_hashcache_cli)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})

function(sweep scene grid folder)
  execute_process(COMMAND ${HPSF} sweep ${scene} --grid "${grid}" --size 24x24 --seeds 2 --reference-spp 32
                          --cache ${dir}/cache --out ${dir}/${folder} --json
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "hpsf sweep ${scene} --grid '${grid}': exit ${code}\n${out}${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

# Every configuration built `expected` times and filled below half its lookups; a sequence's relMSE is that after its
# last frame.
function(check_builds expected)
  string(JSON count LENGTH "${out}" configurations)
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON c GET "${out}" configurations ${i})
    string(JSON id GET "${c}" id)
    string(JSON builds GET "${c}" hashcache builds)
    string(JSON filled GET "${c}" hashcache filled_fraction)
    string(JSON frames GET "${c}" frames)
    if(NOT builds EQUAL expected)
      message(FATAL_ERROR "${id}: ${builds} constructions, expected ${expected}")
    endif()
    execute_process(COMMAND awk "BEGIN { exit !(${filled} >= 0 && ${filled} < 0.5) }" RESULT_VARIABLE failed)
    if(failed)
      message(FATAL_ERROR "${id}: filled fraction ${filled}")
    endif()
    if(frames EQUAL 4)
      string(JSON relmse GET "${c}" relmse)
      string(JSON fourth GET "${c}" relmse_by_frame 3)
      if(NOT fourth STREQUAL relmse)
        message(FATAL_ERROR "${id}: relMSE ${relmse}, after the fourth frame ${fourth}")
      endif()
    endif()
  endforeach()
endfunction()

sweep(cornell "frames=1,4; method=hashcache; backend=reference,emulated,vulkan; cache-resolution=5" static)
check_builds(1)
file(GLOB images ${dir}/static/configs/*.png)
list(LENGTH images image_count)
if(NOT image_count EQUAL 6)
  message(FATAL_ERROR "6 configurations write 6 images, not ${image_count}")
endif()
sweep(${SCENES}/cornell-animated.json "frames=3; method=hashcache; cache-resolution=5" animated)
check_builds(3)
sweep(${SCENES}/cornell-dolly.json "frames=3; method=hashcache; cache-resolution=5" dolly)
check_builds(1)

execute_process(COMMAND ${HPSF} sweep cornell --grid "method=hashcache; accum=packed-decimal" --out ${dir}/bad
                RESULT_VARIABLE code ERROR_VARIABLE err)
if(NOT code EQUAL 3 OR NOT err MATCHES "--grid" OR EXISTS ${dir}/bad)
  message(FATAL_ERROR "packed-decimal sums for the HashCache: exit ${code}, '${err}'")
endif()
