# `hpsf check`, the CI gate: the default gate lists its 36 cases and its shards split them exactly; a gate with a
# defective emulator backend fails with exit 2, its JUnit report validates against tools/gate/junit.xsd (and a
# report broken on purpose does not), names the level in the failure, and the failing case's bundle reproduces it;
# bad gate files and options exit 3 naming the place.
include(${CMAKE_CURRENT_LIST_DIR}/bundle_reproduces.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/hpsf_run.cmake)
set(dir ${OUT}/check_gate)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})

hpsf_run(0 check --list)
string(STRIP "${out}" all)
string(REPLACE "\n" ";" all "${all}")
list(LENGTH all cases)
if(NOT cases EQUAL 36)
  message(FATAL_ERROR "the default gate lists ${cases} cases, expected 36")
endif()
set(sharded)
foreach(shard 1 2 3)
  hpsf_run(0 check --list --shard ${shard}/3)
  string(STRIP "${out}" part)
  string(REPLACE "\n" ";" part "${part}")
  list(APPEND sharded ${part})
endforeach()
list(SORT all)
list(SORT sharded)
if(NOT sharded STREQUAL all)
  message(FATAL_ERROR "shards 1..3 do not hold exactly the gate's cases:\n${sharded}")
endif()

file(WRITE ${dir}/defect.json [=[
{"hpsf_gate": 1,
 "crosscheck": {"scenes": ["cornell"], "size": "24x24", "spp": 1,
   "configs": {"small": {"capacity": 256}},
   "backends": {"emulated": {"backend": "emulated"},
                "emulated-D9": {"backend": "emulated", "inject-defect": "D9", "mode": "faithful", "warp-size": 8}}}}
]=])
hpsf_run(2 check defect.json --junit ${dir}/junit.xml --out ${dir}/out)
if(NOT out MATCHES "PASS crosscheck/cornell/small/emulated/one-frame/seed1"
   OR NOT out MATCHES "FAIL crosscheck/cornell/small/emulated-D9/one-frame/seed1 [^\n]*: level 2 tables: emulated: "
   OR NOT out MATCHES "check: 1 of 2 cases passed")
  message(FATAL_ERROR "the defective gate's output:\n${out}")
endif()
execute_process(COMMAND xmllint --noout --schema ${SCHEMA} ${dir}/junit.xml RESULT_VARIABLE invalid
                ERROR_VARIABLE why)
if(NOT invalid EQUAL 0)
  message(FATAL_ERROR "the JUnit report does not validate:\n${why}")
endif()
file(READ ${dir}/junit.xml junit)
if(NOT junit MATCHES "tests=\"2\" failures=\"1\" errors=\"0\""
   OR NOT junit MATCHES "<failure message=\"level 2 tables: emulated: [^\"]*slot")
  message(FATAL_ERROR "the JUnit report:\n${junit}")
endif()
string(REGEX REPLACE "time=\"[0-9.]+\"" "time=\"soon\"" broken "${junit}")
file(WRITE ${dir}/broken.xml "${broken}")
execute_process(COMMAND xmllint --noout --schema ${SCHEMA} ${dir}/broken.xml RESULT_VARIABLE invalid
                OUTPUT_QUIET ERROR_QUIET)
if(invalid EQUAL 0)
  message(FATAL_ERROR "a JUnit report with time=\"soon\" validates: the schema checks nothing")
endif()
hpsf_expect_bundle_reproduces(${dir}/out/bundles/crosscheck_cornell_small_emulated-D9_one-frame_seed1)

file(WRITE ${dir}/version.json "{\"hpsf_gate\": 2, \"crosscheck\": {}}")
hpsf_run(3 check version.json)
if(NOT err MATCHES "version.json: /hpsf_gate: expected 1")
  message(FATAL_ERROR "gate version 2: ${err}")
endif()
file(WRITE ${dir}/capacity.json [=[
{"hpsf_gate": 1, "crosscheck": {"scenes": ["cornell"], "configs": {"odd": {"capacity": 1000}},
 "backends": {"emulated": {"backend": "emulated"}}}}
]=])
hpsf_run(3 check capacity.json --list)
set(case "crosscheck/cornell/odd/emulated/one-frame/seed1")
if(NOT err MATCHES "capacity.json: case ${case} \\([^)]*/crosscheck/configs/odd[^)]*\\): --capacity")
  message(FATAL_ERROR "a bad capacity: ${err}")
endif()
file(WRITE ${dir}/key.json "{\"hpsf_gate\": 1, \"crosscheck\": {\"scenes\": [\"cornell\"], \"colours\": 3}}")
hpsf_run(3 check key.json)
if(NOT err MATCHES "key.json: /crosscheck/colours: not a gate key")
  message(FATAL_ERROR "an unknown key: ${err}")
endif()
file(WRITE ${dir}/broken.json "{\"hpsf_gate\": 1,")
hpsf_run(3 check broken.json)
if(NOT err MATCHES "broken.json: not valid JSON at byte")
  message(FATAL_ERROR "broken JSON: ${err}")
endif()
hpsf_run(3 check --shard 4/3 --list)
if(NOT err MATCHES "--shard")
  message(FATAL_ERROR "--shard 4/3: ${err}")
endif()
