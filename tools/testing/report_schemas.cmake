# Every JSON report hpsf prints conforms to its published schema (docs/reference/schemas/), on runs that reach each
# report's variants: passing and failing, each backend, frames with eviction, a faithful emulator, identical images
# (PSNR infinite: null), a cached converged image.
# -DHPSF=<hpsf> -DCHECK=<schema_check> -DSOURCE=<hpsf source tree> -DOUT=<scratch folder>
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(schemas ${SOURCE}/docs/reference/schemas)
set(failures "")
set(number 0)
# report(SCHEMA EXPECTED-EXIT ARGS...): runs hpsf ARGS, which prints a JSON report, and checks it against SCHEMA.
function(report schema expected)
  math(EXPR n "${number} + 1")
  set(number ${n} PARENT_SCOPE)
  set(json ${OUT}/report-${n}.json)
  execute_process(COMMAND ${HPSF} ${ARGN} OUTPUT_FILE ${json} ERROR_VARIABLE err RESULT_VARIABLE code
    WORKING_DIRECTORY ${OUT})
  if(NOT code EQUAL expected)
    set(failures "${failures}hpsf ${ARGN}: exit ${code}, expected ${expected}: ${err}\n" PARENT_SCOPE)
    return()
  endif()
  execute_process(COMMAND ${CHECK} ${schemas}/${schema}.schema.json ${json} OUTPUT_VARIABLE out ERROR_VARIABLE out
    RESULT_VARIABLE code)
  if(NOT code EQUAL 0)
    set(failures "${failures}hpsf ${ARGN}:\n${out}\n" PARENT_SCOPE)
  endif()
endfunction()

set(small --size 16x16 --spp 2)
report(render 0 render cornell ${small} -o r.exr --json)
report(render 0 render cornell ${small} --backend emulated --mode faithful --warp-size 8 --frames 3 --eviction strict
  --temporal ema:0.5 --variance --capacity 4096 --compaction occupied-list --fixed-point-bits 40 -o r1.exr --json)
report(render 0 render cornell ${small} --backend vulkan --level-change seed --frames 2 -o r2.exr --json)
report(render 0 render cornell ${small} --seed 2 --no-filter -o r3.exr --json)
report(render 0 render cornell ${small} --backend vulkan --accum float32 --second-moments on --frames 2
  --temporal ema:0.5 -o r4.exr --json)
if(NOT EXISTS ${OUT}/r4.cell-variance.png)
  set(failures "${failures}render --second-moments on wrote no r4.cell-variance.png\n")
endif()
# All or nothing: where the debug image cannot be written, the image and its preview are not left behind either.
file(MAKE_DIRECTORY ${OUT}/r5.cell-variance.png)
execute_process(COMMAND ${HPSF} render cornell ${small} --second-moments on -o r5.exr OUTPUT_QUIET ERROR_QUIET
  RESULT_VARIABLE code WORKING_DIRECTORY ${OUT})
if(NOT code EQUAL 3 OR EXISTS ${OUT}/r5.exr OR EXISTS ${OUT}/r5.png)
  set(failures "${failures}render --second-moments on, its debug image unwritable: exit ${code}, or files left\n")
endif()
report(replay 0 replay ${SOURCE}/tools/testing/data/seed_lookup_alias.hpsfv --backend vulkan -o p.exr --json)
report(crosscheck 0 crosscheck cornell ${small} --backends reference,emulated,vulkan --frames 2 --eviction priority
  --fingerprint-bits 24 --capacity 4096 --json)
report(crosscheck 2 crosscheck cornell ${small} --backends reference,emulated --inject-defect D9 --mode faithful
  --capacity 4096 --repro-dir bundle --json)
report(stats 0 stats cornell ${small} --json)
report(stats 0 stats cornell ${small} --capacity 64 --probe-limit 2 --fingerprint-bits 8 --json)
report(stats 0 stats cornell ${small} --second-moments on --json)
report(crosscheck 0 crosscheck cornell ${small} --backends reference,emulated --second-moments on --frames 2 --json)
report(crosscheck 0 crosscheck cornell ${small} --method hashcache --backends reference,emulated,vulkan --frames 2
       --cache-resolution 5 --json)
report(crosscheck 2 crosscheck cornell ${small} --method hashcache --backends emulated --cache-defect reduce-off-by-one
       --cache-resolution 5 --repro-dir hashcache-repro --json)
execute_process(COMMAND ${HPSF} crosscheck cornell ${small} --backends reference,emulated --capacity 4096 --frames 2
  --eviction strict --capture captures OUTPUT_QUIET RESULT_VARIABLE code WORKING_DIRECTORY ${OUT})
execute_process(COMMAND ${HPSF} crosscheck cornell ${small} --backends reference,emulated --inject-defect D9
  --mode faithful --capacity 4096 --capture captures-d9 --repro-dir bundle-d9 OUTPUT_QUIET ERROR_QUIET
  WORKING_DIRECTORY ${OUT})
report(judge 0 judge captures --json)
report(judge 0 judge captures --rerun captures --json)
report(judge 2 judge captures-d9 --json)
report(stats 0 stats captures/emulated-frame-1.hpsfc --json)
report(diff 0 diff r.exr r.exr --json)
report(diff 2 diff r.exr r3.exr --json)
report(diff 0 diff r.exr r3.exr --metric ssim --warn 0.1 --fail 0.05 --json)
report(fuzz 0 fuzz --backend emulated --runs 20 --seed 1 --json)
report(fuzz 2 fuzz --backend emulated --inject-defect D9 --runs 50 --seed 1 --repro-dir fuzz-bundle --json)
report(device 0 device --json)
report(golden-check 0 golden check --manifest ${SOURCE}/golden/manifest.json cornell-tiny/float32 --json)
file(WRITE ${OUT}/gate.json "{\"hpsf_gate\": 1, \"fuzz\": {\"runs\": 20, \"backends\": {\"d9\": {\"backend\": \"emulated\", \
\"inject-defect\": \"D9\"}}}, \"statistics\": {\"scenes\": [\"cornell\"], \"size\": \"16x16\", \"spp\": 1}}")
report(check 2 check gate.json --out gate-out --json)
report(reference 0 reference cornell --size 16x16 --spp 32 --cache cache --json)
report(reference 0 reference cornell --size 16x16 --spp 32 --cache cache --json)
# The grid's semicolons would split report()'s arguments: the sweep runs here, its report checked the same way.
execute_process(COMMAND ${HPSF} sweep cornell
  --grid "spp=1,2; frames=1,2; method=pt,hpsf,nhpsf,anhpsf; filtered-vertices=2; backend=emulated,vulkan" --seeds 2
  --size 16x16 --reference-spp 32 --cache cache --out sweep --json OUTPUT_FILE ${OUT}/sweep.json ERROR_VARIABLE err
  RESULT_VARIABLE code WORKING_DIRECTORY ${OUT})
execute_process(COMMAND ${CHECK} ${schemas}/sweep.schema.json ${OUT}/sweep.json OUTPUT_VARIABLE out ERROR_VARIABLE out
  RESULT_VARIABLE check)
if(NOT code EQUAL 0 OR NOT check EQUAL 0)
  string(APPEND failures "hpsf sweep: exit ${code}: ${err}${out}\n")
endif()
math(EXPR number "${number} + 1")
if(failures)
  message(FATAL_ERROR "${failures}")
endif()
message(STATUS "${number} reports conform to their schemas")
