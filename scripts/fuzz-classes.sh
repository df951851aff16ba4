#!/usr/bin/env bash
# How fast `hpsf fuzz` finds three classes of bug (a race, a rounding, frame state), unaided: for each broken shader (Vulkan) and
# broken emulator kernel, SEEDS seeds of `hpsf fuzz --runs BUDGET --json`, and per class the runs to find (median
# and max), how many seeds missed, the shrunk records (max) and how many failures were timing-dependent (bundled as
# found). docs/results.md's table comes from this; the ctest budgets (tools/Tests.cmake) are set from its maxima.
# Usage: scripts/fuzz-classes.sh [SEEDS (20)] [BUDGET (2000)]; CLASSES=REGEX picks classes by name; needs
# build/default and jq.
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-20}
budget=${2:-2000}
hpsf=build/default/bin/hpsf
variants=build/default/shader_variants
work=$(mktemp -d "${TMPDIR:-/tmp}/hpsf-fuzz-classes.XXXXXX")
trap 'rm -rf "$work"' EXIT

# name | hpsf fuzz arguments
classes=(
  "rounding: shader D11|--backend vulkan --accumulate-spv $variants/accumulate_D11.spv --accum fixed64"
  "race: shader count store, claim branch first|--backend vulkan --accumulate-spv $variants/accumulate_COUNT_STORE_CLAIM_FIRST.spv --accum fixed64"
  "race: shader count store, join branch first|--backend vulkan --accumulate-spv $variants/accumulate_COUNT_STORE_JOIN_FIRST.spv --accum fixed64"
  "frame state: shader last-seen by the claimer|--backend vulkan --accumulate-spv $variants/accumulate_LAST_SEEN_CLAIMER_ONLY.spv --accum fixed64"
  "rounding: emulator D11|--backend emulated --inject-defect D11"
  "race: emulator count store, claim first|--backend emulated --inject-defect count-store-claim-first"
  "race: emulator count store, join first|--backend emulated --inject-defect count-store-join-first"
  "frame state: emulator last-seen by the claimer|--backend emulated --inject-defect last-seen-claimer-only"
)
printf '| class | found in | runs to find, median / max | shrunk records, max | timing-dependent | seconds |\n'
printf '| --- | --- | --- | --- | --- | --- |\n'
for entry in "${classes[@]}"; do
  name=${entry%%|*}
  [[ -n ${CLASSES:-} && ! $name =~ $CLASSES ]] && continue
  read -r -a args <<<"${entry#*|}"
  start=$SECONDS
  runs=()
  found=0
  shrunk=0
  timing=0
  for ((seed = 1; seed <= seeds; ++seed)); do
    out=$work/report.json
    "$hpsf" fuzz "${args[@]}" --runs "$budget" --seed "$seed" --repro-dir "$work/bundle" --json >"$out" 2>/dev/null || true
    if [[ $(jq -r '.passed' "$out") == false ]]; then
      found=$((found + 1))
      runs+=("$(($(jq -r '.failure.run' "$out") + 1))")
      s=$(jq -r '.failure.shrunk_records' "$out")
      ((s > shrunk)) && shrunk=$s
      [[ $(jq -r '.failure.timing_dependent' "$out") == true ]] && timing=$((timing + 1))
    fi
  done
  if ((found > 0)); then
    sorted=($(printf '%s\n' "${runs[@]}" | sort -n))
    median=${sorted[$(((found - 1) / 2))]}
    max=${sorted[$((found - 1))]}
  else
    median=- max=-
  fi
  printf '| %s | %d of %d seeds | %s / %s | %s | %d | %d |\n' "$name" "$found" "$seeds" "$median" "$max" "$shrunk" "$timing" \
    $((SECONDS - start))
done
