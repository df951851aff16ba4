# A team's shader that writes garbage, as a new user's might: each of SHADERS (accumulate shader variants that leave
# garbage in one output binding, vulkan/shaders/accumulate.glsl) is run through `hpsf crosscheck`, `hpsf fuzz` and
# `hpsf check` with a gate file naming it by a relative path. Each must give exit 2 with the failure named, never a
# crash (exit 4 or a signal), and the gate must list each as a failure with its bundle. Needs HPSF, OUT, VARIANTS
# (the folder of the .spv files) and SHADERS (a list of variant names).
include(${CMAKE_CURRENT_LIST_DIR}/hpsf_run.cmake)
set(dir ${OUT}/untrusted_shader)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir}/shaders)

# What each variant's failure must name: the read-back check's fault, or the contract level that judges the value.
set(named_GARBAGE_KEYS "level 1 keys: FAIL.*record 0: cell_x differs")
set(named_GARBAGE_TAGS "level 2 tables: FAIL")
set(named_GARBAGE_SUMS "level 2 tables: FAIL")
set(named_GARBAGE_COUNTS "level 2 tables: FAIL")
set(named_GARBAGE_PLACEMENTS "invalid shader output: record [0-9]+: placement [0-9]+ is neither a slot below the capacity")
set(named_GARBAGE_STATS "invalid shader output: stats: fixed64 wraps [0-9]+ is more than the run can produce")
set(named_GARBAGE_LAST_SEEN "invalid shader output: slot [0-9]+: last seen in frame [0-9]+, after this frame")
set(named_SLOT0_FOR_FAILURE "invalid shader output: record [0-9]+: placed in slot 0, which is not one of its candidates")

set(cases "")
foreach(shader IN LISTS SHADERS)
  file(COPY ${VARIANTS}/accumulate_${shader}.spv DESTINATION ${dir}/shaders)
  set(options --capacity 1024 --probe-limit 4 --fingerprint-bits 8)
  if(shader STREQUAL "GARBAGE_LAST_SEEN")
    set(options --capacity 1024 --eviction stale:1)
  endif()
  hpsf_run(2 crosscheck cornell --size 48x48 ${options} --backends reference,vulkan
           --accumulate-spv shaders/accumulate_${shader}.spv --accum fixed64 --repro-dir bundle_${shader})
  if(NOT "${out}${err}" MATCHES "${named_${shader}}")
    message(FATAL_ERROR "crosscheck with ${shader}: the failure is not named as '${named_${shader}}':\n${out}${err}")
  endif()
  if(NOT EXISTS ${dir}/bundle_${shader}/reproduce.sh)
    message(FATAL_ERROR "crosscheck with ${shader}: no repro bundle")
  endif()
  # Fuzzing: found, shrunk and reported as a failed check (last-seen frames, read back with eviction only, by
  # the sequences fuzz draws with an eviction policy).
  hpsf_run(2 fuzz --backend vulkan --accumulate-spv shaders/accumulate_${shader}.spv --accum fixed64 --runs 100
           --seed 1 --repro-dir fuzz_${shader})
  if(NOT "${out}${err}" MATCHES "shrunk in [0-9]+ checks")
    message(FATAL_ERROR "fuzz with ${shader}: no shrunk failure:\n${out}${err}")
  endif()
  string(APPEND cases "\"${shader}\": {\"backend\": \"vulkan\", \"accumulate-spv\": \"shaders/accumulate_${shader}.spv\", \"accum\": \"fixed64\"},")
endforeach()
string(REGEX REPLACE ",$" "" cases "${cases}")

# The gate: every variant one case, the shader named relative to the gate file.
file(WRITE ${dir}/gate.json "{\"hpsf_gate\": 1, \"crosscheck\": {\"scenes\": [\"cornell\"], \"size\": \"24x24\", \"spp\": 2,
  \"seeds\": [1], \"configs\": {\"crowded\": {\"capacity\": 256, \"probe-limit\": 4, \"fingerprint-bits\": 8}},
  \"backends\": {${cases}}, \"sequences\": {\"strict\": {\"frames\": 2, \"eviction\": \"stale:1\"}}}}\n")
hpsf_run(2 check gate.json --out gate_out --junit gate.xml --html gate.html)
foreach(shader IN LISTS SHADERS)
  if(NOT out MATCHES "FAIL crosscheck/cornell/crowded/${shader}/strict/seed1")
    message(FATAL_ERROR "the gate does not list ${shader} as a failure:\n${out}${err}")
  endif()
  if(NOT EXISTS ${dir}/gate_out/bundles/crosscheck_cornell_crowded_${shader}_strict_seed1/reproduce.sh)
    message(FATAL_ERROR "the gate kept no bundle for ${shader}:\n${out}${err}")
  endif()
endforeach()
if(out MATCHES "ERROR|crashed")
  message(FATAL_ERROR "the gate reports a crash or an error:\n${out}${err}")
endif()
file(READ ${dir}/gate.xml junit)
string(REGEX MATCHALL "<failure" failures "${junit}")
list(LENGTH failures failed)
list(LENGTH SHADERS expected)
if(NOT failed EQUAL expected)
  message(FATAL_ERROR "gate.xml has ${failed} <failure> elements, expected ${expected}:\n${junit}")
endif()

# A gate bundle whose shader was named by a relative path, moved to a fresh folder after the original shaders are
# gone, reproduces its report (hpsf through $HPSF); through PATH too; with no hpsf it exits 3 saying so; with an
# hpsf of another version it warns.
include(${CMAKE_CURRENT_LIST_DIR}/bundle_reproduces.cmake)
file(REMOVE_RECURSE ${dir}/shaders)
set(bundle ${dir}/gate_out/bundles/crosscheck_cornell_crowded_SLOT0_FOR_FAILURE_strict_seed1)
if(NOT EXISTS ${bundle}/shaders/accumulate.spv)
  message(FATAL_ERROR "the bundle holds no copy of the accumulate shader")
endif()
file(READ ${bundle}/reproduce.sh script)
if(script MATCHES "${dir}|/build/")
  message(FATAL_ERROR "reproduce.sh names a path of this machine:\n${script}")
endif()
if(NOT junit MATCHES "reproduce: sh [^<]*crosscheck_cornell_crowded_SLOT0_FOR_FAILURE_strict_seed1/reproduce.sh")
  message(FATAL_ERROR "the JUnit reproduce line does not point at the bundle's script:\n${junit}")
endif()
hpsf_expect_bundle_reproduces(${bundle})
get_filename_component(hpsf_dir ${HPSF} DIRECTORY)
execute_process(COMMAND ${CMAKE_COMMAND} -E env "PATH=${hpsf_dir}:/usr/bin:/bin" sh ${bundle}/reproduce.sh
                RESULT_VARIABLE code ERROR_VARIABLE said)
if(NOT code EQUAL 2)
  message(FATAL_ERROR "reproduce.sh with hpsf on PATH exited ${code}, expected 2:\n${said}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=HPSF "PATH=/usr/bin:/bin" sh ${bundle}/reproduce.sh
                RESULT_VARIABLE code ERROR_VARIABLE said)
if(NOT code EQUAL 3 OR NOT said MATCHES "no hpsf: set HPSF")
  message(FATAL_ERROR "reproduce.sh without hpsf exited ${code}, expected 3 and a message:\n${said}")
endif()
file(WRITE ${dir}/other/hpsf "#!/bin/sh\nif [ \"$1\" = --version ]; then echo 'hpsf 0.0.0-other'; exit 0; fi\nexec '${HPSF}' \"$@\"\n")
file(CHMOD ${dir}/other/hpsf PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
execute_process(COMMAND ${CMAKE_COMMAND} -E env HPSF=${dir}/other/hpsf sh ${bundle}/reproduce.sh
                RESULT_VARIABLE code ERROR_VARIABLE said)
if(NOT code EQUAL 2 OR NOT said MATCHES "warning: written by hpsf [0-9.]+, reproduced with hpsf 0.0.0-other")
  message(FATAL_ERROR "reproduce.sh with another version exited ${code} without its warning:\n${said}")
endif()
