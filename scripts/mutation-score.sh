#!/usr/bin/env bash
# The mutation score: each patch of mutants/ (the known defects D1-D13 of docs/design/defects.md written into the
# production code, and N1.. for the features built since, one small change each) is applied to a worktree of HEAD,
# built incrementally, and judged by the gate (`hpsf check`: the default gate, then .ci/gate.json) and, when the
# gate passes it, by ctest (-LE "slow|in-gate|mutants": not the check that every patch applies, which an applied
# patch fails; stopping at the first failure, then the gate's own command-line
# test, label gate-cli). A mutant is killed when anything fails or warns, survived when everything passes, and
# stillborn when it does not apply or build (a patch to refresh, not a kill). Prints one line per mutant with what
# caught it, then the score; exits 1 unless every mutant was killed. HPSF_MUTATION_CTEST=always runs ctest after a
# gate kill too, to see which tests would also catch it.
#
#   scripts/mutation-score.sh [NAME...]   names are patch names or prefixes (D7, D11-truncated-fixed-point)
#
# HPSF_MUTATION_DIR (default build/mutation) holds the worktree, its build and the logs; the worktree is reset
# to HEAD and reused, so a second run builds only what the mutants touch.
set -euo pipefail
root=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
work=${HPSF_MUTATION_DIR:-$root/build/mutation}
tree=$work/tree
mkdir -p "$work/logs"

if [ ! -d "$tree/.git" ] && [ ! -f "$tree/.git" ]; then
  git -C "$root" worktree add --detach "$tree" HEAD > /dev/null
fi
git -C "$tree" checkout --detach --force "$(git -C "$root" rev-parse HEAD)" > /dev/null 2>&1
git -C "$tree" reset --hard > /dev/null
git -C "$tree" clean -fdq -e build

patches=()
if [ $# -eq 0 ]; then
  patches=("$root"/mutants/*.patch)
else
  for name in "$@"; do
    found=("$root"/mutants/"$name"*.patch)
    [ -e "${found[0]}" ] || { echo "mutation-score: no mutant named $name in mutants/" >&2; exit 3; }
    patches+=("${found[@]}")
  done
fi

start=$(date +%s)
(cd "$tree" && cmake --preset default > "$work/logs/configure.log" 2>&1 && cmake --build --preset default > "$work/logs/build-HEAD.log" 2>&1) ||
  { echo "mutation-score: HEAD does not build in $tree (see $work/logs)" >&2; exit 3; }
hpsf=$tree/build/default/bin/hpsf

killed=0
total=0
for patch in "${patches[@]}"; do
  name=$(basename "$patch" .patch)
  total=$((total + 1))
  log=$work/logs/$name
  git -C "$tree" reset --hard > /dev/null
  if ! git -C "$tree" apply "$patch" 2> "$log.apply"; then
    printf '%-34s stillborn: the patch does not apply (%s)\n' "$name" "$log.apply"
    continue
  fi
  if ! (cd "$tree" && cmake --build --preset default) > "$log.build" 2>&1; then
    printf '%-34s stillborn: does not build (%s)\n' "$name" "$log.build"
    continue
  fi
  caught=()
  for gate in "" "$tree/.ci/gate.json"; do
    out=$work/gate-$name-$([ -z "$gate" ] && echo default || echo project)
    rm -rf "$out"
    if ! (cd "$tree" && "$hpsf" check $gate --out "$out") > "$log.gate" 2>&1; then
      caught+=("gate: $(grep -m1 -E '^(FAIL|WARN|ERROR) ' "$log.gate" | cut -c1-110 || echo 'exit code')")
      break
    fi
  done
  if [ ${#caught[@]} -eq 0 ] || [ "${HPSF_MUTATION_CTEST:-}" = always ]; then
    if ! (cd "$tree/build/default" && ctest -j2 -LE "slow|in-gate|mutants" --stop-on-failure --timeout 600 &&
          ctest -L gate-cli --timeout 600) > "$log.ctest" 2>&1; then
      first=$(grep -m1 -E '\*\*\*(Failed|Timeout|Exception)' "$log.ctest" | sed -E 's/^ *[0-9]+\/[0-9]+ Test +#[0-9]+: ([^ ]+).*/\1/')
      caught+=("ctest: ${first:-failed}")
    fi
  fi
  if [ ${#caught[@]} -gt 0 ]; then
    killed=$((killed + 1))
    joined=${caught[0]}
    [ ${#caught[@]} -gt 1 ] && joined="$joined; ${caught[1]}"
    printf '%-34s killed by %s\n' "$name" "$joined"
  else
    printf '%-34s SURVIVED the gate and ctest\n' "$name"
  fi
done
git -C "$tree" reset --hard > /dev/null
echo "mutation score: $killed of $total killed ($(( $(date +%s) - start )) s)"
[ "$killed" -eq "$total" ]
