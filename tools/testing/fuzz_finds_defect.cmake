# `hpsf fuzz ARGS` (a ;-list) must find a failure (exit 2) within its --runs, shrink it to at most MAX_RECORDS
# records (over every frame), and leave a repro bundle whose reproduce.sh (`hpsf crosscheck records.hpsfv ...`)
# fails again with the same report, bit for bit. With TIMING_DEPENDENT, a race: the failure must name EXPECT and leave
# a bundle, not reproduced here. A race fails on some runs only, so fuzz usually reports it as timing-dependent and
# bundles it as found; when it happened to fail on every rerun, fuzz shrinks it instead, and either outcome is right.
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
if(TIMING_DEPENDENT)
  string(JSON first ERROR_VARIABLE no_tables_failure GET "${out}" failure report levels 1 failures 0)
  if(NOT first MATCHES "${EXPECT}" OR NOT EXISTS ${dir}/bundle/records.hpsfv)
    message(FATAL_ERROR "expected a failure naming '${EXPECT}', bundled:
${out}")
  endif()
  return()
endif()
if(shrunk GREATER MAX_RECORDS)
  message(FATAL_ERROR "shrunk to ${shrunk} records, expected at most ${MAX_RECORDS}")
endif()
hpsf_expect_bundle_reproduces(${dir}/bundle)
