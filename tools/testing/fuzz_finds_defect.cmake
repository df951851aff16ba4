# `hpsf fuzz ARGS` (a ;-list) must find a failure (exit 2) within its --runs, shrink it to at most MAX_RECORDS
# records, and leave a repro bundle whose reproduce.sh (`hpsf crosscheck records.hpsfv ...`) fails again with
# the same report, bit for bit.
include(${CMAKE_CURRENT_LIST_DIR}/bundle_reproduces.cmake)
set(dir ${OUT}/${NAME})
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
execute_process(COMMAND ${HPSF} fuzz ${ARGS} --repro-dir ${dir}/bundle --json
                WORKING_DIRECTORY ${dir} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${err}")
if(NOT code EQUAL 2)
  message(FATAL_ERROR "hpsf fuzz exited ${code}, expected 2 (a failure found)\n${out}")
endif()
string(JSON run GET "${out}" failure run)
string(JSON seconds GET "${out}" failure seconds_to_find)
string(JSON found GET "${out}" failure records)
string(JSON shrunk GET "${out}" failure shrunk_records)
string(JSON shrunk_case GET "${out}" failure shrunk_case)
message("found at run ${run} after ${seconds} s: ${found} records, shrunk to ${shrunk}: ${shrunk_case}")
if(shrunk GREATER MAX_RECORDS)
  message(FATAL_ERROR "shrunk to ${shrunk} records, expected at most ${MAX_RECORDS}")
endif()
hpsf_expect_bundle_reproduces(${dir}/bundle)
