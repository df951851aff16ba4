# hpsf golden on a copy of golden/: a one-pixel change of a fixed64 golden fails its case for every backend,
# names the case and leaves the new image, the heatmap and its report beside the golden; bless rewrites that golden alone
# and says what changed, after which the case passes; a shared golden is blessed by its first case; the statistical case passes another seed and fails a 1%
# bias; a bad manifest is bad input naming the file and the case.
set(dir ${OUT}/golden_cli)
file(REMOVE_RECURSE ${dir})
file(COPY ${GOLDEN} DESTINATION ${dir})
set(golden ${dir}/golden)

function(run code regex)
  execute_process(COMMAND ${HPSF} golden ${ARGN} RESULT_VARIABLE got OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("hpsf golden ${ARGN}: exit ${got}\n${out}${err}")
  if(NOT got EQUAL code)
    message(FATAL_ERROR "hpsf golden ${ARGN}: exit ${got}, expected ${code}")
  endif()
  if(NOT "${out}${err}" MATCHES "${regex}")
    message(FATAL_ERROR "hpsf golden ${ARGN}: the output does not match '${regex}'")
  endif()
  set(output "${out}${err}" PARENT_SCOPE)
endfunction()

# One pixel of a golden, (10, 20), set to 0.25 (oiiotool keeps the hpsf: metadata).
function(change_pixel exr)
  execute_process(COMMAND oiiotool ${exr} --box:color=0.25,0.25,0.25:fill=1 10,20,10,20 -o ${exr} RESULT_VARIABLE code)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "oiiotool could not change ${exr}")
  endif()
endfunction()

change_pixel(${golden}/cornell-fixed64.exr)
run(2 "FAIL  cornell/fixed64 +reference FAIL: max .* at \\(10, 20, .\\).*FAIL  cornell/fixed64 +emulated.*FAIL  cornell/fixed64 +vulkan.*PASS  furnace/fixed64.*6 checks of 2 cases: 3 pass, 0 warn, 3 fail"
    check --manifest ${golden}/manifest.json cornell/fixed64 furnace/fixed64)
foreach(backend reference emulated vulkan)
  foreach(artifact new.exr heatmap.png report.html)
    if(NOT EXISTS ${golden}/cornell-fixed64.${backend}.${artifact})
      message(FATAL_ERROR "the failing case left no cornell-fixed64.${backend}.${artifact}")
    endif()
  endforeach()
endforeach()
if(EXISTS ${golden}/furnace-fixed64.reference.new.exr)
  message(FATAL_ERROR "a passing case left its new image behind")
endif()

run(0 "blessed +cornell/fixed64 .*changed: FAIL: max .* at \\(10, 20, .\\) is above --fail 0" bless --manifest ${golden}/manifest.json cornell/fixed64)
if(output MATCHES "furnace")
  message(FATAL_ERROR "bless touched a golden it was not asked for")
endif()
run(0 "3 checks of 1 cases: 3 pass" check --manifest ${golden}/manifest.json cornell/fixed64)
if(EXISTS ${golden}/cornell-fixed64.reference.new.exr)
  message(FATAL_ERROR "a case that passes again still has the new image of its failure beside it")
endif()

# A golden two cases share is its first case's: blessing the second (float32 on the hashed backends, compared
# within 1e-4) renders with the first case's backend (the reference), so the first case's exact check still
# passes; rendered by the emulator or Vulkan, float32 sums in another order would fail it.
change_pixel(${golden}/cornell-float32.exr)
run(0 "blessed +cornell/float32 +.*cornell-float32.exr \\(changed: .*rendered by reference\\)"
    bless --manifest ${golden}/manifest.json cornell/float32-hashed)
run(0 "1 checks of 1 cases: 1 pass" check --manifest ${golden}/manifest.json cornell/float32)

# The statistical case survives another seed and fails a 1% bias: the manifest's last case renders the Cornell
# floor at seed 1; here at seed 2, first against its golden (consistent with noise), then against the golden
# with green scaled by 0.99 (its image-mean test rejects; power 0.99 by statistical_compare_test's figures).
file(READ ${golden}/manifest.json manifest)
string(JSON cases LENGTH "${manifest}" cases)
math(EXPR last "${cases} - 1")
string(JSON name GET "${manifest}" cases ${last} name)
string(JSON seed_flag GET "${manifest}" cases ${last} args 4)
if(NOT name STREQUAL "cornell-floor/statistical" OR NOT seed_flag STREQUAL "--seed")
  message(FATAL_ERROR "the manifest's last case is not the statistical Cornell floor at args[4] --seed")
endif()
string(JSON manifest SET "${manifest}" cases ${last} args 5 "\"2\"")
file(WRITE ${golden}/manifest.json "${manifest}")
run(0 "PASS  cornell-floor/statistical +reference PASS: consistent with noise.*2 checks of 1 cases: 2 pass"
    check --manifest ${golden}/manifest.json cornell-floor/statistical)
execute_process(COMMAND oiiotool ${golden}/cornell-floor-statistical.exr --mulc 1,0.99,1,1,1,1,1,1,1
                        -o ${golden}/cornell-floor-statistical.exr RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "oiiotool could not scale the statistical golden")
endif()
run(2 "FAIL  cornell-floor/statistical +reference FAIL: NOT consistent with noise.*0 pass, 0 warn, 2 fail"
    check --manifest ${golden}/manifest.json cornell-floor/statistical)
foreach(artifact new.exr heatmap.png report.html)
  if(NOT EXISTS ${golden}/cornell-floor-statistical.reference.${artifact})
    message(FATAL_ERROR "the failing statistical case left no ${artifact}")
  endif()
endforeach()

# Bad manifests: exit 3, the file and the case named.
file(WRITE ${dir}/broken.json "{\"hpsf_golden\": 1, \"cases\": [")
run(3 "broken.json: not valid JSON" check --manifest ${dir}/broken.json)
file(WRITE ${dir}/unknown.json "{\"hpsf_golden\": 1, \"cases\": [{\"name\": \"x\", \"scene\": \"cornell\", \"backends\": [\"reference\"], \"golden\": \"x.exr\", \"tolerance\": 1}]}")
run(3 "unknown.json: case 0 \\(x\\): unknown field 'tolerance'" check --manifest ${dir}/unknown.json)
file(WRITE ${dir}/both.json "{\"hpsf_golden\": 1, \"cases\": [{\"name\": \"y\", \"scene\": \"cornell\", \"records\": \"r.hpsfv\", \"backends\": [\"reference\"], \"golden\": \"y.exr\"}]}")
run(3 "both.json: case 0 \\(y\\): give exactly one of scene and records" check --manifest ${dir}/both.json)
run(3 "no case named 'nosuch'" check --manifest ${golden}/manifest.json nosuch)
run(3 "cannot open the golden manifest" check --manifest ${dir}/missing.json)
