// The gate has teeth: the broken variants of the accumulate kernel (emulated/defect_injection), one per known
// defect of docs/design/defects.md (D2, D3, D8, D9, D13), run on inputs constructed to reach the defect. For each, the
// table checker or the cross-check contract must fail. D9 and D13 need a particular interleaving: the tests report
// which schedule policies found them and after how many schedules.
#include <bit>
#include <cstdio>
#include <functional>
#include <optional>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/hash_table.h"
#include "core/input_check.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "emulated/simt/kernel_fault.h"
#include "emulated/simt/schedule.h"
#include "property_tests/constructed_cells.h"
#include "verifier/checker/table_checker.h"

namespace hpsf {
namespace {

using testing::BatchOfCells;
using testing::ConstructedConfig;
using testing::FindCell;

std::vector<TableViolation> CheckRun(const RecordBatch& batch, const EmulatedRun& run) {
  return CheckTable({run.table, batch.records, run.keys, run.placements});
}

EmulatedRun RunFaithful(const RecordBatch& batch, const FilterConfig& config, AccumulateKernelFn kernel,
                        const std::string& schedule = "round-robin", std::uint32_t warp_size = 8) {
  EmulatorOptions options;
  options.mode = simt::Mode::kFaithful;
  options.warp_size = warp_size;
  options.schedule = schedule;
  return EmulatedFilter(batch, config, options, kernel);
}

TEST(BrokenKernels, CorrectKernelPassesOnEveryConstructedInput) {
  const FilterConfig config = ConstructedConfig(64, 4, 8);
  const glm::ivec3 zero =
      FindCell(config, [](const KeyResult& k) { return (shared::FullFingerprint(k.words) >> 24) == 0u; });
  const glm::ivec3 last = FindCell(config, [](const KeyResult& k) { return k.slot0 == 63u; });
  const RecordBatch batch = BatchOfCells({zero, zero, last, last, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}});
  EXPECT_TRUE(CheckRun(batch, RunFaithful(batch, config, AccumulateKernel)).empty());
}

// Each broken kernel is the correct one with exactly one change: on an input that does not reach its defect (one
// record, one probe, a slot away from the end, a 32-bit fingerprint that is not 0) it passes, in both modes. hpsf
// fuzz found that the mutants once added fixed point into float32 tables and reduced D3's fingerprint to 8 bits
// whatever the width, so they failed on anything, and a fuzzer "found" them without reaching their defects.
TEST(BrokenKernels, EachMutantPassesAnInputThatDoesNotReachItsDefect) {
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    FilterConfig config = ConstructedConfig(64, 1, 32);
    config.accumulation = accumulation;
    const glm::ivec3 cell = FindCell(config, [](const KeyResult& k) { return k.slot0 == 10u && k.fingerprint > 1u; });
    const RecordBatch batch = BatchOfCells({cell});
    for (const Defect defect :
         {Defect::kD2AddsAgain, Defect::kD3ZeroFingerprint, Defect::kD8ClampedProbe, Defect::kD8UnwrappedProbe,
          Defect::kD9NonAtomicAdd, Defect::kD13LoadThenStoreClaim, Defect::kD11TruncatedFixedPoint,
          Defect::kCountStoreClaimFirst, Defect::kCountStoreJoinFirst, Defect::kLastSeenClaimerOnly}) {
      const auto violations = CheckRun(batch, RunFaithful(batch, config, KernelWithDefect(defect)));
      EXPECT_TRUE(violations.empty()) << ToString(defect) << " in " << ToString(accumulation) << ": "
                                      << violations.front().ToString();
    }
  }
}

TEST(BrokenKernels, D2AddingAgainAfterAMatchIsCaught) {
  const FilterConfig config = ConstructedConfig(64, 4);
  const RecordBatch batch = BatchOfCells({{1, 2, 3}, {1, 2, 3}, {9, 9, 9}});
  const auto violations = CheckRun(batch, RunFaithful(batch, config, KernelWithDefect(Defect::kD2AddsAgain)));
  ASSERT_FALSE(violations.empty());
  std::printf("D2 caught: %s\n", violations.front().ToString().c_str());
}

TEST(BrokenKernels, D3AZeroFingerprintIsCaught) {
  // A key whose 8-bit fingerprint reduces to 0: the mutant "claims" its slot with the empty tag.
  const FilterConfig config = ConstructedConfig(64, 4, 8);
  const glm::ivec3 zero =
      FindCell(config, [](const KeyResult& k) { return (shared::FullFingerprint(k.words) >> 24) == 0u; });
  const RecordBatch batch = BatchOfCells({zero, zero});
  const auto violations = CheckRun(batch, RunFaithful(batch, config, KernelWithDefect(Defect::kD3ZeroFingerprint)));
  ASSERT_FALSE(violations.empty());
  std::printf("D3 caught: %s\n", violations.front().ToString().c_str());
}

TEST(BrokenKernels, D8AClampedProbeIsCaught) {
  // Keys whose window wraps past capacity - 1: two keys at slot0 = 63 make the second probe.
  const FilterConfig config = ConstructedConfig(64, 4);
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 63u; });
  const glm::ivec3 b = FindCell(
      config, [](const KeyResult& k) { return k.slot0 == 63u; }, a.x + 1);
  const RecordBatch batch = BatchOfCells({a, b});
  const auto violations = CheckRun(batch, RunFaithful(batch, config, KernelWithDefect(Defect::kD8ClampedProbe)));
  ASSERT_FALSE(violations.empty());
  std::printf("D8 caught: %s\n", violations.front().ToString().c_str());
}

TEST(BrokenKernels, D8AnUnwrappedProbeFaultsOutOfBoundsInBothModes) {
  // The second key at slot0 = 63 probes slot 64 of a 64-slot table: the emulator stops the kernel there.
  const FilterConfig config = ConstructedConfig(64, 4);
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 63u; });
  const glm::ivec3 b = FindCell(
      config, [](const KeyResult& k) { return k.slot0 == 63u; }, a.x + 1);
  const RecordBatch batch = BatchOfCells({a, b});
  const AccumulateKernelFn kernel = KernelWithDefect(Defect::kD8UnwrappedProbe);
  EmulatorOptions fast;
  for (const auto& run : std::vector<std::function<void()>>{[&] { RunFaithful(batch, config, kernel); },
                                                            [&] { EmulatedFilter(batch, config, fast, kernel); }}) {
    try {
      run();
      ADD_FAILURE() << "the unwrapped probe did not fault";
    } catch (const simt::KernelFault& fault) {
      EXPECT_THAT(fault.what(), ::testing::HasSubstr("out-of-bounds access to buffer 'tags' at index 64 of 64"));
      std::printf("D8 unwrapped caught: %s\n", fault.what());
    }
  }
  EXPECT_TRUE(CheckRun(batch, RunFaithful(batch, config, AccumulateKernel)).empty());  // the input is fine
}

// D9 and D13 depend on the interleaving: try each policy over seeds and report after how many schedules it
// first produced a table the checker rejects.
struct Hunt {
  std::string policy;
  int schedules_until_caught = -1;  // -1: not caught within the budget
};

std::vector<Hunt> HuntDefect(const RecordBatch& batch, const FilterConfig& config, AccumulateKernelFn kernel,
                             std::uint32_t warp_size) {
  std::vector<Hunt> hunts;
  auto caught = [&](const std::string& schedule) {
    return !CheckRun(batch, RunFaithful(batch, config, kernel, schedule, warp_size)).empty();
  };
  hunts.push_back({"round-robin", caught("round-robin") ? 1 : -1});
  for (const std::string family : {"random", "pct:2", "pct:3"}) {
    Hunt hunt{family, -1};
    for (int seed = 0; seed < 200 && hunt.schedules_until_caught < 0; ++seed) {
      const std::string schedule =
          family == "random" ? "random:" + std::to_string(seed) : "pct:" + std::to_string(seed) + family.substr(3);
      if (caught(schedule)) hunt.schedules_until_caught = seed + 1;
    }
    hunts.push_back(hunt);
  }
  return hunts;
}

// Exhaustive search on a launch small enough to enumerate (two threads of the accumulate kernel, warp size 1):
// the schedule at which the checker first rejects the table, and how many schedules were explored (all of
// them, unless asked to stop at the first rejection).
struct ExhaustiveHunt {
  std::uint64_t caught_at = 0;  // 0: never
  std::uint64_t schedules = 0;
  bool complete = false;  // every schedule of the launch explored
};

enum class Stop { kAtFirstCatch, kNever };

ExhaustiveHunt HuntExhaustively(const RecordBatch& batch, const FilterConfig& config, AccumulateKernelFn kernel,
                                Stop stop) {
  simt::ExhaustiveSchedule schedule;
  EmulatorOptions options;
  options.mode = simt::Mode::kFaithful;
  options.warp_size = 1;
  options.schedule_instance = &schedule;
  ExhaustiveHunt hunt;
  do {
    ++hunt.schedules;  // every schedule must run: the search learns the next one from this run's decisions
    if (!CheckRun(batch, EmulatedFilter(batch, config, options, kernel)).empty() && hunt.caught_at == 0) {
      hunt.caught_at = hunt.schedules;
      if (stop == Stop::kAtFirstCatch) return hunt;
    }
  } while (schedule.Advance());
  hunt.complete = true;
  return hunt;
}

void ReportExhaustive(const char* defect, const ExhaustiveHunt& hunt) {
  std::printf("%s with exhaustive (2 threads): caught at schedule %llu%s\n", defect, (unsigned long long)hunt.caught_at,
              hunt.complete ? (" of " + std::to_string(hunt.schedules) + " in all").c_str() : "");
  EXPECT_GT(hunt.caught_at, 0u) << defect << " escaped exhaustive search";
}

void Report(const char* defect, const std::vector<Hunt>& hunts) {
  bool any = false;
  for (const Hunt& h : hunts) {
    std::printf("%s with %-11s: %s\n", defect, h.policy.c_str(),
                h.schedules_until_caught < 0
                    ? "not caught in 200 schedules"
                    : ("caught after " + std::to_string(h.schedules_until_caught) + " schedule(s)").c_str());
    any = any || h.schedules_until_caught > 0;
  }
  EXPECT_TRUE(any) << defect << " escaped every policy";
}

TEST(BrokenKernels, D9LostUpdatesAreCaughtAndReportedPerPolicy) {
  // Eight records of one cell in different warps (warp size 1): their load-then-store adds can interleave.
  const FilterConfig config = ConstructedConfig(64, 4);
  const RecordBatch batch = BatchOfCells(std::vector<glm::ivec3>(8, glm::ivec3(5, 5, 5)));
  Report("D9", HuntDefect(batch, config, KernelWithDefect(Defect::kD9NonAtomicAdd), 1));
  const RecordBatch two = BatchOfCells(std::vector<glm::ivec3>(2, glm::ivec3(5, 5, 5)));
  // This launch has about half a million schedules: stop at the first rejection.
  ReportExhaustive("D9", HuntExhaustively(two, config, KernelWithDefect(Defect::kD9NonAtomicAdd), Stop::kAtFirstCatch));
  // The correct kernel passes every one of its schedules on the same launch.
  const ExhaustiveHunt correct = HuntExhaustively(two, config, AccumulateKernel, Stop::kNever);
  EXPECT_EQ(correct.caught_at, 0u);
  std::printf("correct kernel, one cell, exhaustive (2 threads): %llu schedules, all pass\n",
              (unsigned long long)correct.schedules);
  // Within one warp the lanes load together and store in turn: every schedule loses updates.
  EXPECT_FALSE(
      CheckRun(batch, RunFaithful(batch, config, KernelWithDefect(Defect::kD9NonAtomicAdd), "round-robin", 8)).empty());
}

TEST(BrokenKernels, D13TwoKeysRacingForOneEmptySlotAreCaughtAndReportedPerPolicy) {
  const FilterConfig config = ConstructedConfig(64, 4);
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 17u; });
  const glm::ivec3 b = FindCell(
      config, [](const KeyResult& k) { return k.slot0 == 17u; }, a.x + 1);
  const RecordBatch batch = BatchOfCells({a, b, a, b});
  Report("D13", HuntDefect(batch, config, KernelWithDefect(Defect::kD13LoadThenStoreClaim), 1));
  const RecordBatch two = BatchOfCells({a, b});
  ReportExhaustive("D13",
                   HuntExhaustively(two, config, KernelWithDefect(Defect::kD13LoadThenStoreClaim), Stop::kNever));
  const ExhaustiveHunt correct = HuntExhaustively(two, config, AccumulateKernel, Stop::kNever);
  EXPECT_EQ(correct.caught_at, 0u);
  std::printf("correct kernel, two keys racing, exhaustive (2 threads): %llu schedules, all pass\n",
              (unsigned long long)correct.schedules);
}

}  // namespace
}  // namespace hpsf
