# `hpsf crosscheck --inject-defect D9` must fail with exit code 2 and write a repro bundle whose reproduce.sh
# fails again with the same report.
include(${CMAKE_CURRENT_LIST_DIR}/bundle_reproduces.cmake)
set(dir ${OUT}/defect)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
execute_process(COMMAND ${HPSF} crosscheck cornell --size 24x24 --capacity 256 --mode faithful --warp-size 8 --inject-defect D9 --backends reference,emulated
                        --repro-dir ${dir}/bundle
                WORKING_DIRECTORY ${dir} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT code EQUAL 2)
  message(FATAL_ERROR "crosscheck with an injected defect exited ${code}, expected 2")
endif()
hpsf_expect_bundle_reproduces(${dir}/bundle)

# A traced sequence with the tracer's decisions (survival's culls, a path graph's own lights): its bundle holds them in
# records.hpsfv (version 4 for the own lights) and reruns the check without --survival and --path-graph, which a
# record file refuses, so it fails again the same way.
execute_process(COMMAND ${HPSF} crosscheck cornell --size 24x24 --frames 2 --second-moments on
                        --survival linear:0.001:0.01 --path-graph 0.001 --interpolation smooth:0.001:0.01
                        --capacity 256 --mode faithful --warp-size 8 --inject-defect D9 --backends reference,emulated
                        --repro-dir ${dir}/adaptive-bundle
                WORKING_DIRECTORY ${dir} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT code EQUAL 2)
  message(FATAL_ERROR "crosscheck of an adaptive sequence with an injected defect exited ${code}, expected 2")
endif()
file(READ ${dir}/adaptive-bundle/reproduce.sh script)
if(script MATCHES "--survival|--path-graph")
  message(FATAL_ERROR "the bundle's check names the tracer's options, which a record file refuses:\n${script}")
endif()
hpsf_expect_bundle_reproduces(${dir}/adaptive-bundle)
