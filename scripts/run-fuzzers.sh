#!/usr/bin/env bash
# Runs each libFuzzer target of tools/fuzz over its checked-in corpus for a bounded time (CI: after
# `cmake --preset fuzz && cmake --build --preset fuzz`). The corpus is copied to a temporary directory, so the
# checked-in one never changes. Prints each target's executions per second and coverage; exits 1 if any target
# found a crash, a timeout or a leak, keeping the input under build/fuzz/crashes and printing how to reproduce it.
# Usage: scripts/run-fuzzers.sh [SECONDS_PER_TARGET] (default 20); HPSF_FUZZ_TARGETS="fuzz_table ..." picks some;
# HPSF_FUZZ_JOBS targets run at once (default: the number of cores).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-20}
bin=build/fuzz/bin
crashes=build/fuzz/crashes
read -r -a targets <<<"${HPSF_FUZZ_TARGETS:-fuzz_table fuzz_checker fuzz_read_back fuzz_scene fuzz_obj fuzz_hpsfv fuzz_cli fuzz_declaration fuzz_capture fuzz_hashcache}"
declare -A dictionaries=([fuzz_scene]="json.dict obj.dict" [fuzz_obj]="obj.dict" [fuzz_hpsfv]="hpsfv.dict" [fuzz_cli]="cli.dict"
                         [fuzz_declaration]="json.dict declaration.dict" [fuzz_capture]="capture.dict json.dict declaration.dict")

work=$(mktemp -d "${TMPDIR:-/tmp}/hpsf-fuzz.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$crashes"
for target in "${targets[@]}"; do
  [[ -x "$bin/$target" ]] || { echo "run-fuzzers: $bin/$target is missing: cmake --preset fuzz && cmake --build --preset fuzz" >&2; exit 2; }
done

# One target: its log in $work/TARGET.log, its exit status in $work/TARGET.status.
fuzz() {
  local target=$1 status=0
  cp -r "tools/fuzz/corpus/$target" "$work/$target"
  local options=(-seed=1 -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
                 -artifact_prefix="$crashes/$target-")
  if [[ -n "${dictionaries[$target]:-}" ]]; then
    for dictionary in ${dictionaries[$target]}; do cat "tools/fuzz/$dictionary"; done >"$work/$target.dict"
    options+=(-dict="$work/$target.dict")
  fi
  "$bin/$target" "${options[@]}" "$work/$target" >"$work/$target.log" 2>&1 || status=$?
  echo "$status" >"$work/$target.status"
}

# Each target is one process on one core: as many run at once as there are cores (HPSF_FUZZ_JOBS), so a run
# takes about SECONDS x targets / cores. A target's executions per second are those of one core either way.
parallel=${HPSF_FUZZ_JOBS:-$(nproc)}
start=$SECONDS
for target in "${targets[@]}"; do
  while (($(jobs -rp | wc -l) >= parallel)); do wait -n || true; done
  fuzz "$target" &
done
wait

failed=()
printf '%-13s %8s %7s %7s %7s %9s\n' target seconds exec/s cov ft corpus
for target in "${targets[@]}"; do
  log="$work/$target.log"
  status=$(cat "$work/$target.status" 2>/dev/null || echo "no status")
  # libFuzzer's last status line ("#N DONE cov: C ft: F corp: U/S ...") and its final statistics.
  last=$(grep -E '^#[0-9]+' "$log" | tail -n 1 || true)
  cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$last")
  ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
  corpus=$(sed -nE 's/.* corp: ([0-9]+\/[0-9]+[a-zA-Z]*).*/\1/p' <<<"$last")
  rate=$(sed -nE 's/^stat::average_exec_per_sec: *([0-9]+)/\1/p' "$log")
  printf '%-13s %8s %7s %7s %7s %9s\n' "$target" "$seconds" "${rate:-?}" "${cov:-?}" "${ft:-?}" "${corpus:-?}"
  if [[ $status != 0 ]]; then
    failed+=("$target")
    echo "run-fuzzers: $target failed (exit $status):" >&2
    grep -vE '^(#[0-9]+|INFO:|\s*$)' "$log" | tail -n 40 >&2
    for artifact in $(sed -nE 's/.*Test unit written to (.*)$/\1/p' "$log"); do
      echo "run-fuzzers: reproduce with: $bin/$target $artifact" >&2
    done
    cp "$log" "$crashes/$target.log"
  fi
done
echo "run-fuzzers: ${#targets[@]} targets, $parallel at a time, in $((SECONDS - start)) s"
if ((${#failed[@]} > 0)); then
  echo "run-fuzzers: FAILED: ${failed[*]} (inputs and logs in $crashes/)" >&2
  exit 1
fi
