# hpsf judge on captures hpsf's own host wrote (crosscheck --capture): the verdict, exit code and JUnit of a clean
# shader and of a broken one are the host's; a capture that is not one exits 3 and, in a directory with good ones,
# leaves no output at all (no verdicts printed, no JUnit file).
# -DHPSF=<hpsf> -DOUT=<scratch folder> -DVARIANTS=<shader variant folder>
set(dir ${OUT}/judge_cli)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
set(run crosscheck cornell --size 24x24 --spp 2 --capacity 256 --fingerprint-bits 8 --backends reference,vulkan
  --repro-dir ${dir}/repro)

function(run_hpsf expect_code)
  execute_process(COMMAND ${HPSF} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expect_code)
    message(FATAL_ERROR "hpsf ${ARGN}: exited ${code}, expected ${expect_code}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect_match text pattern what)
  if(NOT "${text}" MATCHES "${pattern}")
    message(FATAL_ERROR "${what} does not match '${pattern}':\n${text}")
  endif()
endfunction()

# The clean shader: the host passes, and so does its capture, in text and JUnit.
run_hpsf(0 ${run} --capture ${dir}/clean)
run_hpsf(0 judge ${dir}/clean --junit ${dir}/clean.xml)
expect_match("${out}" "vulkan-frame-0.hpsfc: PASS" "judge's output")
expect_match("${out}" "level 2 tables: PASS" "judge's output")
file(READ ${dir}/clean.xml junit)
expect_match("${junit}" "<testcase classname=\"judge/clean\" name=\"judge/clean/vulkan-frame-0.hpsfc\"" "the JUnit report")

# D2's shader adds again after a match: the host fails level 2, and so does its capture, named the same way.
run_hpsf(2 ${run} --accumulate-spv ${VARIANTS}/accumulate_D2.spv --capture ${dir}/d2)
expect_match("${out}" "level 2 tables: FAIL" "the host's output")
run_hpsf(2 judge ${dir}/d2 --junit ${dir}/d2.xml)
expect_match("${out}" "level 2 tables: FAIL[^\n]*\n  capture: earlier slot of the window empty or matching" "judge's output")
file(READ ${dir}/d2.xml junit)
expect_match("${junit}" "<failure message=\"level 2 tables: capture: earlier slot" "the JUnit report")
run_hpsf(2 judge ${dir}/d2/vulkan-frame-0.hpsfc --json)
expect_match("${out}" "\"passed\": false" "judge's JSON")

# A capture cut short: exit 3 naming it; beside a good one, nothing printed and no JUnit written.
file(READ ${dir}/clean/vulkan-frame-0.hpsfc bytes HEX LIMIT 4000)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "\\\\x\\1" escaped "${bytes}")
file(MAKE_DIRECTORY ${dir}/mixed)
file(COPY ${dir}/clean/vulkan-frame-0.hpsfc DESTINATION ${dir}/mixed)
execute_process(COMMAND printf "${escaped}" OUTPUT_FILE ${dir}/mixed/z-cut.hpsfc)
run_hpsf(3 judge ${dir}/mixed/z-cut.hpsfc)
expect_match("${err}" "z-cut.hpsfc: byte [0-9]+: " "judge's error")
run_hpsf(3 judge ${dir}/mixed --junit ${dir}/mixed.xml)
if(NOT "${out}" STREQUAL "" OR EXISTS ${dir}/mixed.xml)
  message(FATAL_ERROR "a bad capture among good ones left output behind:\n${out}")
endif()
run_hpsf(3 judge ${dir}/repro-does-not-exist.hpsfc)
expect_match("${err}" "cannot open the capture" "judge's error")

# The captures family of a gate file: one case per folder, the clean one passing and D2's failing, in JUnit too.
file(WRITE ${dir}/gate.json "{\"hpsf_gate\": 1, \"captures\": {\"paths\": [\"d2\", \"clean\"]}}")
run_hpsf(2 check ${dir}/gate.json --out ${dir}/gate-out --junit ${dir}/gate.xml)
expect_match("${out}" "PASS captures/clean" "the gate's output")
expect_match("${out}" "FAIL captures/d2 \\([0-9.]+ s\\): [^\n]*vulkan-frame-0.hpsfc: level 2 tables: capture: earlier slot"
  "the gate's output")
file(READ ${dir}/gate.xml junit)
expect_match("${junit}" "<testsuite name=\"captures\" tests=\"2\" failures=\"1\"" "the gate's JUnit report")
file(WRITE ${dir}/missing.json "{\"hpsf_gate\": 1, \"captures\": {\"paths\": [\"clean\", \"nowhere\"]}}")
run_hpsf(3 check ${dir}/missing.json --out ${dir}/missing-out)
expect_match("${err}" "missing.json: /captures/paths/1: .*nowhere: no such capture or folder" "the gate's error")
