# `hpsf check`, the CI gate: the default gate lists its 66 cases and its shards split them exactly; a gate with a
# defective emulator backend fails with exit 2, its JUnit report validates against verifier/gate/junit.xsd (and a
# report broken on purpose does not), names the level in the failure, and the failing case's bundle reproduces it;
# its two shards, run apart and merged (--merge), give the unsharded report, JUnit and HTML page, and bad merges
# exit 3; a gate of every family (statistics, goldens on a copy of golden/ with one golden changed, a fuzz budget
# against a defective emulator) warns and fails where it must, with exit 1 for warnings alone; bad gate files and
# options exit 3 naming the place.
include(${CMAKE_CURRENT_LIST_DIR}/bundle_reproduces.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/hpsf_run.cmake)
# A JUnit report that validates against the schema CI systems accept; the test fails naming `what` otherwise.
function(expect_valid_junit file what)
  execute_process(COMMAND xmllint --noout --schema ${SCHEMA} ${file} RESULT_VARIABLE invalid ERROR_VARIABLE why)
  if(NOT invalid EQUAL 0)
    message(FATAL_ERROR "${what} does not validate:\n${why}")
  endif()
endfunction()

set(dir ${OUT}/check_gate)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})

hpsf_run(0 check --list)
string(STRIP "${out}" all)
string(REPLACE "\n" ";" all "${all}")
list(LENGTH all cases)
if(NOT cases EQUAL 66)
  message(FATAL_ERROR "the default gate lists ${cases} cases, expected 66")
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
expect_valid_junit(${dir}/junit.xml "the JUnit report")
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

# Shards on two "machines", merged: the same report as the unsharded run above (its out/check.json), case for case
# in gate order, times and bundle paths (and the reproduce lines that point into the bundles) aside; the merged
# JUnit validates and holds the same cases.
function(normalized_report text result)
  string(REGEX REPLACE "\"seconds\": [0-9.e+-]+" "\"seconds\": T" text "${text}")
  string(REGEX REPLACE "\"bundle\": \"[^\"]*\"" "\"bundle\": B" text "${text}")
  string(REGEX REPLACE "\"reproduce\": \"sh [^\"]*/reproduce.sh\"" "\"reproduce\": R" text "${text}")
  string(REGEX REPLACE "\"shard\": \"[^\"]*\"" "\"shard\": S" text "${text}")
  string(STRIP "${text}" text)
  set(${result} "${text}" PARENT_SCOPE)
endfunction()
hpsf_run(0 check defect.json --shard 1/2 --out ${dir}/shard1)
hpsf_run(2 check defect.json --shard 2/2 --out ${dir}/shard2)
hpsf_run(2 check --merge ${dir}/shard2 ${dir}/shard1 --json --junit ${dir}/merged.xml --html ${dir}/merged.html)
normalized_report("${out}" merged)
file(READ ${dir}/out/check.json whole)
normalized_report("${whole}" whole)
if(NOT merged STREQUAL whole)
  message(FATAL_ERROR "the merged shards' report:\n${merged}\nthe unsharded report:\n${whole}")
endif()
if(NOT merged MATCHES "\"index\": 0,.*\"index\": 1,")
  message(FATAL_ERROR "the merged report is not in gate order:\n${merged}")
endif()
expect_valid_junit(${dir}/merged.xml "the merged JUnit report")
file(READ ${dir}/merged.xml merged_junit)
string(REGEX REPLACE "time=\"[0-9.]+\"" "" merged_junit "${merged_junit}")
string(REGEX REPLACE "time=\"[0-9.]+\"" "" unsharded_junit "${junit}")
string(REGEX REPLACE "repro bundle: [^\n<]*" "" merged_junit "${merged_junit}")
string(REGEX REPLACE "repro bundle: [^\n<]*" "" unsharded_junit "${unsharded_junit}")
string(REGEX REPLACE "reproduce: sh [^\n<]*/reproduce.sh" "" merged_junit "${merged_junit}")
string(REGEX REPLACE "reproduce: sh [^\n<]*/reproduce.sh" "" unsharded_junit "${unsharded_junit}")
if(NOT merged_junit STREQUAL unsharded_junit)
  message(FATAL_ERROR "the merged JUnit report:\n${merged_junit}\nthe unsharded one:\n${unsharded_junit}")
endif()
file(READ ${dir}/merged.html merged_html)
if(NOT merged_html MATCHES "<tr class=\"case pass\"[^>]*>.*<td>1</td>.*crosscheck/cornell/small/emulated/one-frame/seed1"
   OR NOT merged_html MATCHES "<tr class=\"case fail\"[^>]*>.*<td>2</td>.*emulated-D9.*level 2 tables: emulated: "
   OR NOT merged_html MATCHES "<td>crosscheck</td><td>2</td><td>1</td><td>0</td><td>1</td>")
  message(FATAL_ERROR "the merged HTML page:\n${merged_html}")
endif()
hpsf_run(3 check --merge ${dir}/shard1)
if(NOT err MATCHES "--merge: case 1 of [^\n]*defect.json is in none of the reports: a shard is missing")
  message(FATAL_ERROR "a missing shard: ${err}")
endif()
hpsf_run(3 check --merge ${dir}/shard1 ${dir}/shard1)
if(NOT err MATCHES "shard1/check.json: case crosscheck/cornell/small/emulated/one-frame/seed1 is in [^\n]*shard1/check.json too")
  message(FATAL_ERROR "a shard given twice: ${err}")
endif()
file(WRITE ${dir}/bad/check.json "{\"version\": 1, \"command\": \"check\", \"gate\": 3}")
hpsf_run(3 check --merge ${dir}/bad)
if(NOT err MATCHES "bad/check.json: /gate: not a string")
  message(FATAL_ERROR "a bad report: ${err}")
endif()
hpsf_run(3 check defect.json --merge ${dir}/shard1)
if(NOT err MATCHES "--merge: merges the reports")
  message(FATAL_ERROR "--merge beside a gate file: ${err}")
endif()

# Every family. A copy of golden/ with one pixel of the fixed64 furnace golden moved (oiiotool keeps the metadata)
# and a manifest of three cases on it: the furnace replayed against its golden (fails on every backend), against
# the fixed64 Cornell golden with only a warning threshold (warns), and in float32 (passes).
file(COPY ${GOLDEN} DESTINATION ${dir})
execute_process(COMMAND oiiotool ${dir}/golden/furnace-fixed64.exr --box:color=0.25,0.25,0.25:fill=1 3,4,3,4
                        -o ${dir}/golden/furnace-fixed64.exr RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "oiiotool could not change the golden")
endif()
file(WRITE ${dir}/golden/gate-manifest.json [=[
{"hpsf_golden": 1, "cases": [
  {"name": "furnace/changed", "records": "records/furnace.hpsfv", "args": ["--accum", "fixed64", "--capacity", "65536"],
   "backends": ["reference", "vulkan"], "golden": "furnace-fixed64.exr", "comparison": "exact"},
  {"name": "furnace/warned", "records": "records/furnace.hpsfv", "args": ["--accum", "fixed64", "--capacity", "65536"],
   "backends": ["reference"], "golden": "cornell-fixed64.exr", "comparison": "exact", "warn": 0, "fail": 1e9},
  {"name": "furnace/float32", "records": "records/furnace.hpsfv", "args": ["--accum", "float32", "--capacity", "65536"],
   "backends": ["reference"], "golden": "furnace-float32.exr", "comparison": "exact"}]}
]=])
file(WRITE ${dir}/families.json [=[
{"hpsf_gate": 1,
 "statistics": {"scenes": ["cornell"], "size": "32x32", "spp": 1, "configs": {"small": {"capacity": 4096}}},
 "golden": {"manifest": "golden/gate-manifest.json"},
 "fuzz": {"runs": 300, "seeds": [3],
          "backends": {"emulated": {"backend": "emulated"}, "emulated-D9": {"backend": "emulated", "inject-defect": "D9"}}}}
]=])
hpsf_run(2 check families.json --junit ${dir}/families.xml --html ${dir}/families/gate.html --out ${dir}/families)
foreach(line "PASS statistics/cornell/small/seed1"
             "FAIL golden/furnace/changed [^\n]*: furnace/changed on reference: FAIL: max [^\n]* at \\(3, 4, "
             "PASS golden/furnace/float32" "WARN golden/furnace/warned [^\n]*: furnace/warned on reference: WARN"
             "PASS fuzz/emulated/seed3"
             "FAIL fuzz/emulated-D9/seed3 [^\n]*: level 2 tables: emulated: [^\n]* at run [0-9]+ \\([a-z-]+, [0-9]+ records, shrunk to [12]\\)"
             "statistics: 1 of 1 passed" "golden: 1 of 3 passed, 1 warned, 1 failed" "fuzz: 1 of 2 passed, 1 failed"
             "check: 3 of 6 cases passed")
  if(NOT out MATCHES "${line}")
    message(FATAL_ERROR "the families gate's output lacks '${line}':\n${out}")
  endif()
endforeach()
expect_valid_junit(${dir}/families.xml "the families' JUnit report")
file(READ ${dir}/families.xml junit)
if(NOT junit MATCHES "<testsuite name=\"golden\" tests=\"3\" failures=\"1\" errors=\"0\""
   OR NOT junit MATCHES "name=\"golden/furnace/warned\" time=\"[0-9.]+\">\n      <system-out>warning: furnace/warned")
  message(FATAL_ERROR "the families' JUnit report:\n${junit}")
endif()
file(READ ${dir}/families/gate.html html)
string(REGEX MATCHALL "<tr class=\"case " rows "${html}")
list(LENGTH rows rows)
if(NOT rows EQUAL 6 OR NOT html MATCHES "<a href=\"html/golden_furnace_changed.html\">the case's report</a>"
   OR NOT html MATCHES "<td>golden</td><td>3</td><td>1</td><td>1</td><td>1</td><td>0</td>")
  message(FATAL_ERROR "the families' HTML page (${rows} rows):\n${html}")
endif()
if(NOT EXISTS ${dir}/families/html/golden_furnace_changed.html)
  message(FATAL_ERROR "the golden case left no report of its comparisons")
endif()
hpsf_expect_bundle_reproduces(${dir}/families/bundles/fuzz_emulated-D9_seed3)
# Warnings alone exit 1.
file(WRITE ${dir}/warned.json [=[
{"hpsf_gate": 1, "golden": {"manifest": "golden/gate-manifest.json", "cases": ["furnace/warned", "furnace/float32"]}}
]=])
hpsf_run(1 check warned.json --out ${dir}/warned)
if(NOT out MATCHES "golden: 1 of 2 passed, 1 warned" OR NOT out MATCHES "check: 1 of 2 cases passed")
  message(FATAL_ERROR "a gate that only warns:\n${out}")
endif()
file(WRITE ${dir}/fuzz-time.json "{\"hpsf_gate\": 1, \"fuzz\": {\"time\": 60, \"backends\": {}}}")
hpsf_run(3 check fuzz-time.json --list)
if(NOT err MATCHES "fuzz-time.json: /fuzz/time: a gate's fuzz budget is \"runs\"")
  message(FATAL_ERROR "a fuzz budget in seconds: ${err}")
endif()
file(WRITE ${dir}/golden-case.json "{\"hpsf_gate\": 1, \"golden\": {\"manifest\": \"golden/gate-manifest.json\", \"cases\": [\"furnace/none\"]}}")
hpsf_run(3 check golden-case.json --list)
if(NOT err MATCHES "golden-case.json: /golden/cases/0: not a case of [^\n]*gate-manifest.json")
  message(FATAL_ERROR "an unknown golden case: ${err}")
endif()
file(WRITE ${dir}/stats-option.json [=[
{"hpsf_gate": 1, "statistics": {"scenes": ["cornell"], "configs": {"odd": {"probe-limit": 0}}}}
]=])
hpsf_run(3 check stats-option.json --list)
if(NOT err MATCHES "stats-option.json: case statistics/cornell/odd/seed1 \\([^)]*/statistics/configs/odd\\): --probe-limit")
  message(FATAL_ERROR "a bad statistics option: ${err}")
endif()
file(WRITE ${dir}/empty.json "{\"hpsf_gate\": 1, \"name\": \"nothing\"}")
hpsf_run(3 check empty.json)
if(NOT err MATCHES "empty.json: the gate declares no family to run")
  message(FATAL_ERROR "a gate of no family: ${err}")
endif()

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
