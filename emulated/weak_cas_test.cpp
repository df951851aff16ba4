// The emulator's weak compare-and-swap (emulated/simt/memory_op.h, kAtomicCasWeak): without a policy it is the strong
// one; with one it fails spuriously, replayed from the step and the lane; and it separates a claim written as a
// retry loop, correct under any share of spurious failures, from Bevy #24767's claim read from the old value alone.
#include <set>

#include <gtest/gtest.h>

#include "core/error.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "emulated/simt/launcher.h"
#include "property_tests/constructed_cells.h"
#include "verifier/checker/table_checker.h"

namespace hpsf {
namespace {

using simt::ThreadContext;

// Each thread adds one to a counter by a weak compare-and-swap in a loop, counting its spurious failures.
simt::KernelTask WeakIncrement(ThreadContext& ctx, std::uint32_t counter) {
  std::uint64_t seen = co_await ctx.Load(counter, 0);
  for (;;) {
    const ThreadContext::CasResult swap = co_await ctx.AtomicCasWeak(counter, 0, seen, seen + 1);
    if (swap.exchanged) break;
    seen = swap.old;
  }
}

struct Counted {
  std::uint64_t value = 0, spurious = 0, trace = 0;
};

Counted Increment(double probability, std::uint32_t seed) {
  simt::DeviceMemory memory;
  const std::uint32_t counter = memory.Allocate64("counter", 1);
  simt::RandomSchedule schedule(seed);
  const simt::LaunchReport report = simt::LaunchFaithful(
      memory, 64, 8, [&](ThreadContext& ctx) { return WeakIncrement(ctx, counter); }, schedule, {},
      simt::WeakCasPolicy{probability});
  return {memory.Words64(counter)[0], report.stats.spurious_cas_failures, report.trace_hash};
}

TEST(WeakCas, FailsSpuriouslyOnlyUnderAPolicyAndReplaysItsFailures) {
  const Counted strong = Increment(0.0, 1);
  EXPECT_EQ(strong.value, 64u);
  EXPECT_EQ(strong.spurious, 0u);
  const Counted weak = Increment(0.5, 1);
  EXPECT_EQ(weak.value, 64u);  // the loop retries every spurious failure
  EXPECT_GT(weak.spurious, 32u);
  const Counted again = Increment(0.5, 1);
  EXPECT_EQ(again.spurious, weak.spurious);
  EXPECT_EQ(again.trace, weak.trace);
  EXPECT_NE(weak.trace, strong.trace);
}

// Crowded constructed cells, faithful warps of 8 under random schedules: the retry loop's table passes the checker at
// every share of spurious failures; the old-value claim fails it as soon as one claim fails spuriously.
TEST(WeakCas, TheRetryLoopIsCorrectAndTheOldValueClaimIsNot) {
  const FilterConfig config = testing::ConstructedConfig(16, 4, 8);
  std::vector<glm::ivec3> cells;
  for (int i = 0; i < 40; ++i) cells.push_back({i % 11, i % 3, 7});
  const RecordBatch batch = testing::BatchOfCells(cells);
  int caught = 0;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    EmulatorOptions options;
    options.mode = simt::Mode::kFaithful;
    options.warp_size = 8;
    options.schedule = "random:" + std::to_string(seed);
    options.spurious_cas = 0.5;
    const EmulatedRun loop = EmulatedFilter(batch, config, options, AccumulateWithWeakCas);
    EXPECT_GT(loop.launch.stats.spurious_cas_failures, 0u) << seed;
    const std::vector<TableViolation> clean = CheckTable({loop.table, batch.records, loop.keys, loop.placements});
    EXPECT_TRUE(clean.empty()) << seed << ": " << clean.front().ToString();
    const EmulatedRun old_value = EmulatedFilter(batch, config, options, KernelWithDefect(Defect::kWeakCasOldValue));
    caught += !CheckTable({old_value.table, batch.records, old_value.keys, old_value.placements}).empty();
  }
  EXPECT_EQ(caught, 20);
  EmulatorOptions fast;
  fast.spurious_cas = 0.5;
  EXPECT_THROW(fast.Validate(), ConfigError);  // fast mode runs the CPU's compare-and-swap
}

}  // namespace
}  // namespace hpsf
