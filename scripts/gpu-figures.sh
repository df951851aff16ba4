#!/usr/bin/env bash
# The GPU checks and figures on a machine with a GPU, in one device call, so that a session lent one for a
# short while spends it measuring. Two steps:
#   here, after a build:      scripts/gpu-figures.sh pack    (the binaries and their libraries into .gpu-bundle/)
#   there, from the repo root: bash scripts/gpu-figures.sh run  (carry .gpu-bundle; writes $OUT, else ./gpu-figures)
# `run` records each step's exit status in status.txt and goes on after a failure, so one call shows everything.
# It needs NVIDIA's driver: .gpu-bundle/run.sh points the Vulkan loader at it alone, so here every Vulkan step
# fails with "no Vulkan driver could create an instance" (the emulator's steps still run).
set -uo pipefail
# Not hpsf itself: OpenImageIO's dependencies would take the bundle past what a device call carries (64 MiB).
binaries=(key_identity_tests fixed_point_identity_tests vulkan_backend_tests vulkan_benchmark emulator_benchmark)
# The property tests that run Vulkan (ctest label vulkan) but not the hpsf tool: on a GPU of subgroup size 32 they
# check what lavapipe's 8 cannot (eviction, temporal, compaction and level-seed shaders on a real device).
property_binaries=(broken_shader_tests compaction_tests eviction_tests priority_eviction_tests temporal_blend_tests
  temporal_integration_tests crosscheck_frames_tests level_seed_tests probing_schemes_tests capture_judgement_tests
  hard_case_tests count_overflow_tests fingerprint_alias_tests full_key_tests packed_sums_tests)

case "${1:-}" in
  pack)
    set -e
    scripts/gpu-bundle.sh build/default/bin "${binaries[@]}" "${property_binaries[@]}"
    # The property tests read scenes and shader variants at the paths they were built with: take the variants along
    # and remember this checkout's path, which `run` links to the copy there.
    rm -rf .gpu-bundle/shader_variants && cp -r build/default/shader_variants .gpu-bundle/
    pwd > .gpu-bundle/source_dir
    ;;
  run)
    out=${OUT:-gpu-figures}
    mkdir -p "$out"
    # A step that hangs (a driver, a deadlocked kernel) ends at its limit (rc=124) so the others still run.
    step() {  # step NAME COMMAND...: output in NAME.txt, exit status in status.txt
      local name=$1; shift
      local start=$SECONDS
      timeout "${GPU_FIGURES_STEP_LIMIT_S:-200}" "$@" > "$out/$name.txt" 2>&1
      echo "$name rc=$? $((SECONDS - start))s" >> "$out/status.txt"
    }
    bundle=(bash .gpu-bundle/run.sh)
    aggregates=(--benchmark_repetitions=3 --benchmark_report_aggregates_only=true)
    : > "$out/status.txt"
    step machine sh -c 'nvidia-smi; nproc; lscpu'
    step key_identity "${bundle[@]}" key_identity_tests --gtest_brief=1
    step fixed_point_identity "${bundle[@]}" fixed_point_identity_tests --gtest_brief=1
    step vulkan_backend "${bundle[@]}" vulkan_backend_tests --gtest_brief=1
    step vulkan_benchmark "${bundle[@]}" vulkan_benchmark "${aggregates[@]}" \
      --benchmark_out="$out/vulkan_benchmark.json" --benchmark_out_format=json
    grep -q "ERROR OCCURRED" "$out/vulkan_benchmark.txt" &&
      echo "vulkan_benchmark: a benchmark failed" >> "$out/status.txt"
    # The emulator on every core and on two of the same machine: its scaling with cores (target 5x from 2 to 16).
    step emulator_all_cores "${bundle[@]}" emulator_benchmark "${aggregates[@]}" --benchmark_filter='Raw|Fast' \
      --benchmark_out="$out/emulator_all_cores.json" --benchmark_out_format=json
    step emulator_2_cores taskset -c 0,1 bash .gpu-bundle/run.sh emulator_benchmark "${aggregates[@]}" \
      --benchmark_filter='Raw|Fast' --benchmark_out="$out/emulator_2_cores.json" --benchmark_out_format=json
    source_dir=$(cat .gpu-bundle/source_dir 2>/dev/null)
    if [ -n "$source_dir" ] && [ ! -e "$source_dir" ]; then mkdir -p "$(dirname "$source_dir")" && ln -s "$PWD" "$source_dir"; fi
    mkdir -p build/default
    [ -e build/default/shader_variants ] || ln -s "$PWD/.gpu-bundle/shader_variants" build/default/shader_variants
    for b in "${property_binaries[@]}"; do step "$b" "${bundle[@]}" "$b" --gtest_brief=1; done
    cat "$out/status.txt"
    ;;
  *)
    echo "usage: scripts/gpu-figures.sh pack|run" >&2
    exit 2
    ;;
esac
