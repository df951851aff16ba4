#!/usr/bin/env bash
# The sanitizer runs of CI (.ci/run calls this): AddressSanitizer + UndefinedBehaviorSanitizer over the test suite
# (the asan preset), and ThreadSanitizer over the emulator's fast mode and the tracer (the tsan preset, whose
# loops run on plain threads TSan can see: core/parallel_for.h). Any report fails the run. Each phase's wall time
# is printed, for CI's budget.
#   scripts/run-sanitizers.sh [asan|tsan|all]   (default all)
# The asan run is the suite without the labels slow (the statistics suites and the twenty-fold cross-check, 10 of
# the 17 minutes the suite takes under ASan at -O1) and golden (full renders); ASAN_CTEST_ARGS replaces that
# selection, e.g. ASAN_CTEST_ARGS=" " for the whole suite.
set -euo pipefail
cd "$(dirname "$0")/.."
which=${1:-all}
case "$which" in asan | tsan | all) ;; *) echo "usage: $0 [asan|tsan|all]" >&2 && exit 2 ;; esac
supp=$PWD/scripts/sanitizers
jobs=$(nproc)

phase() {
  local name=$1 start=$SECONDS
  shift
  "$@"
  echo "run-sanitizers: $name: $((SECONDS - start)) s"
}

if [[ $which != tsan ]]; then
  # Every report ends the process that makes it with a non-zero code, so the test that ran it fails; leaks are
  # reported at exit. No suppression is needed: lavapipe and LLVM run clean under it, once the Vulkan drivers stay
  # loaded until exit (vulkan/driver_pinning.h: unloaded, lavapipe's one-time allocations read as leaks).
  export ASAN_OPTIONS=detect_leaks=1:check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  phase "asan configure" cmake --preset asan
  phase "asan build" cmake --build --preset asan
  read -r -a extra <<<"${ASAN_CTEST_ARGS:--LE slow|golden}"  # words, never globbed
  phase "asan ctest" ctest --preset asan -j "$jobs" "${extra[@]}"
  unset ASAN_OPTIONS UBSAN_OPTIONS
fi

if [[ $which != asan ]]; then
  # halt_on_error with an exit code of its own: the first race ends the test binary with 66. tsan.supp names only
  # Debian's uninstrumented Embree (whose BVH build still runs on TBB's threads).
  export TSAN_OPTIONS="halt_on_error=1:exitcode=66:second_deadlock_stack=1:suppressions=$supp/tsan.supp"
  export RC_PARAMS="seed=20261121 max_success=500"  # as ctest gives them (cmake/Tests.cmake)
  phase "tsan configure" cmake --preset tsan
  phase "tsan build" cmake --build --preset tsan
  # Not ctest: the tsan build holds only these three test binaries. Each test runs on all cores.
  for test in simt_tests emulated_tests tracer_tests; do
    phase "tsan $test" build/tsan/bin/$test --gtest_brief=1
  done
fi
echo "run-sanitizers: $which: clean"
