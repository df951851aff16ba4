# `hpsf crosscheck --method hashcache` (docs/design/hashcache.md): the HashCache on every backend over frames of
# cornell-animated (a construction a frame) passes with exit 0 and a report of two passed levels; the emulator's reduce
# one element long fails with exit 2, writes a bundle whose reproduce.sh fails the same way, and names the seed; bad
# HashCache options are bad input (exit 3) naming the option.
set(dir ${OUT}/hashcache_crosscheck_cli)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
set(small --size 16x16 --spp 1 --cache-resolution 5)

execute_process(COMMAND ${HPSF} crosscheck ${SCENES}/cornell-animated.json --method hashcache --frames 3
                        --backends reference,emulated,vulkan ${small} --json
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the HashCache on every backend: exit ${code}\n${out}${err}")
endif()
foreach(level 0 1)
  string(JSON passed GET "${out}" levels ${level} passed)
  if(NOT passed)
    message(FATAL_ERROR "level ${level} did not pass:\n${out}")
  endif()
endforeach()
foreach(backend 0 1 2)
  string(JSON builds GET "${out}" hashcache backends ${backend} builds)
  if(NOT builds EQUAL 3)
    message(FATAL_ERROR "cornell-animated over 3 frames builds 3 times, not ${builds}:\n${out}")
  endif()
endforeach()

execute_process(COMMAND ${HPSF} crosscheck cornell --method hashcache --backends reference,emulated ${small}
                        --cache-defect reduce-off-by-one --repro-dir ${dir}/bundle
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 2 OR NOT out MATCHES "emulated: 1 frames, 1 constructions: [0-9]+ problems, the first: update 0"
   OR NOT err MATCHES "seed 1" OR NOT EXISTS ${dir}/bundle/reproduce.sh)
  message(FATAL_ERROR "the reduce one element long: exit ${code}\n${out}${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env HPSF=${HPSF} sh ${dir}/bundle/reproduce.sh
                RESULT_VARIABLE code ERROR_VARIABLE err)
file(READ ${dir}/bundle/reproduced.json reproduced)
string(JSON passed GET "${reproduced}" passed)
if(NOT code EQUAL 2 OR passed)
  message(FATAL_ERROR "the bundle's reproduce.sh: exit ${code}, passed ${passed}\n${err}")
endif()

foreach(case "--cache-defect;hidden;--cache-defect" "--cache-update;locks;--cache-update"
             "--cache-resolution;11;--cache-resolution" "--cache-store;0;--cache-store" "--method;kd;--method"
             "--cache-defect;reduce-off-by-one;--cache-defect")
  list(GET case 0 option)
  list(GET case 1 value)
  list(GET case 2 named)
  execute_process(COMMAND ${HPSF} crosscheck cornell --method hashcache --backends vulkan --size 8x8 --spp 1
                          ${option} ${value}
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 3 OR NOT err MATCHES "${named}")
    message(FATAL_ERROR "${option} ${value}: exit ${code}, '${err}'")
  endif()
endforeach()
