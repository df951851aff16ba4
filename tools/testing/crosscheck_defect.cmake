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
