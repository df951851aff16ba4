// Litmus kernels with known outcome sets check the scheduler itself: the exhaustive policy must find exactly
// the possible outcomes, in exactly as many schedules as the combinatorics predicts.
#include <set>

#include <gtest/gtest.h>

#include "core/error.h"
#include "emulated/simt/launcher.h"

namespace hpsf::simt {
namespace {

// counter = counter + 1 as a plain load and a plain store: a lost update waiting to happen (docs/design/defects.md,
// D9).
KernelTask NonAtomicIncrement(ThreadContext& ctx, std::uint32_t counter) {
  const std::uint64_t value = co_await ctx.Load(counter, 0);
  co_await ctx.Store(counter, 0, value + 1);
}

KernelTask CasIncrement(ThreadContext& ctx, std::uint32_t counter) {
  std::uint64_t seen = co_await ctx.Load(counter, 0);
  while (true) {
    const std::uint64_t old = co_await ctx.AtomicCas(counter, 0, seen, seen + 1);
    if (old == seen) break;
    seen = old;
  }
}

KernelTask AtomicIncrement(ThreadContext& ctx, std::uint32_t counter) { co_await ctx.AtomicAdd(counter, 0, 1); }

using KernelOf = KernelTask (*)(ThreadContext&, std::uint32_t);

struct Exploration {
  std::set<std::uint64_t> outcomes;
  std::uint64_t schedules = 0;
  std::set<std::uint64_t> trace_hashes;
};

Exploration ExploreCounter(KernelOf kernel, std::uint32_t threads, std::uint32_t warp_size) {
  Exploration e;
  ExhaustiveSchedule schedule;
  do {
    DeviceMemory memory;
    const std::uint32_t counter = memory.Allocate32("counter", 1);
    const LaunchReport report = LaunchFaithful(
        memory, threads, warp_size, [&](ThreadContext& ctx) { return kernel(ctx, counter); }, schedule);
    e.outcomes.insert(memory.Words32(counter)[0]);
    e.trace_hashes.insert(report.trace_hash);
    ++e.schedules;
  } while (schedule.Advance());
  return e;
}

TEST(Litmus, NonAtomicIncrementInTwoWarpsGivesOneOrTwoInSixSchedules) {
  const Exploration e = ExploreCounter(NonAtomicIncrement, 2, 1);
  EXPECT_EQ(e.outcomes, (std::set<std::uint64_t>{1, 2}));
  EXPECT_EQ(e.schedules, 6u);            // interleavings of 2 + 2 operations: 4! / (2! 2!)
  EXPECT_EQ(e.trace_hashes.size(), 6u);  // each schedule leaves its own trace
}

TEST(Litmus, ThreeWarpsExploreTheMultinomialNumberOfSchedules) {
  const Exploration e = ExploreCounter(NonAtomicIncrement, 3, 1);
  EXPECT_EQ(e.schedules, 90u);  // 6! / (2! 2! 2!)
  EXPECT_EQ(e.outcomes, (std::set<std::uint64_t>{1, 2, 3}));
}

TEST(Litmus, OneWarpLosesTheUpdateInBothOrdersOfItsConflictingStores) {
  // Both loads happen in one warp step; the two stores conflict, and either order leaves 1.
  const Exploration e = ExploreCounter(NonAtomicIncrement, 2, 2);
  EXPECT_EQ(e.outcomes, (std::set<std::uint64_t>{1}));
  EXPECT_EQ(e.schedules, 2u);
}

TEST(Litmus, CasIncrementAlwaysGivesTwo) {
  for (std::uint32_t warp_size : {1u, 2u}) {
    const Exploration e = ExploreCounter(CasIncrement, 2, warp_size);
    EXPECT_EQ(e.outcomes, (std::set<std::uint64_t>{2})) << "warp size " << warp_size;
    EXPECT_GT(e.schedules, 1u);
  }
  EXPECT_EQ(ExploreCounter(CasIncrement, 3, 1).outcomes, (std::set<std::uint64_t>{3}));
}

TEST(Litmus, AtomicIncrementAlwaysCounts) {
  EXPECT_EQ(ExploreCounter(AtomicIncrement, 3, 1).outcomes, (std::set<std::uint64_t>{3}));
  EXPECT_EQ(ExploreCounter(AtomicIncrement, 3, 1).schedules, 6u);  // 3! orders of one operation each
}

// Sixteen threads in warps of four race on one counter with plain and atomic operations.
std::uint64_t TraceOf(const std::string& policy, std::uint64_t* counted = nullptr) {
  DeviceMemory memory;
  const std::uint32_t plain = memory.Allocate32("plain", 1), atomic = memory.Allocate32("atomic", 1);
  auto schedule = MakeSchedule(policy, 4, 64);
  const LaunchReport report = LaunchFaithful(
      memory, 16, 4,
      [&](ThreadContext& ctx) -> KernelTask {
        return [](ThreadContext& c, std::uint32_t p, std::uint32_t a) -> KernelTask {
          co_await c.AtomicAdd(a, 0, 1);
          const std::uint64_t v = co_await c.Load(p, 0);
          co_await c.Store(p, 0, v + 1);
        }(ctx, plain, atomic);
      },
      *schedule);
  EXPECT_EQ(memory.Words32(atomic)[0], 16u) << policy;
  if (counted) *counted = memory.Words32(plain)[0];
  return report.trace_hash;
}

TEST(Schedules, SameSeedSameTraceOtherSeedOtherTrace) {
  EXPECT_EQ(TraceOf("random:1"), TraceOf("random:1"));
  EXPECT_NE(TraceOf("random:1"), TraceOf("random:2"));
  EXPECT_EQ(TraceOf("pct:5:3"), TraceOf("pct:5:3"));
  EXPECT_NE(TraceOf("pct:5:3"), TraceOf("pct:6:3"));
  EXPECT_EQ(TraceOf("round-robin"), TraceOf("round-robin"));
}

TEST(Schedules, RandomSchedulesLoseUpdatesOfThePlainCounter) {
  std::set<std::uint64_t> counts;
  for (std::uint32_t seed = 0; seed < 20; ++seed) {
    std::uint64_t counted = 0;
    TraceOf("random:" + std::to_string(seed), &counted);
    counts.insert(counted);
  }
  EXPECT_LT(*counts.begin(), 16u) << "no schedule lost an update";
}

TEST(Schedules, BadPolicyNamesTheOption) {
  EXPECT_THROW(MakeSchedule("random:", 1, 1), ConfigError);
  EXPECT_THROW(MakeSchedule("pct:1", 1, 1), ConfigError);
  EXPECT_THROW(MakeSchedule("pct:1:0", 1, 1), ConfigError);
  EXPECT_THROW(MakeSchedule("fifo", 1, 1), ConfigError);
}

TEST(FastMode, AtomicsCountEveryThreadOnAllCores) {
  DeviceMemory memory;
  const std::uint32_t counter = memory.Allocate64("counter", 1);
  LaunchFast(memory, 100000, [&](ThreadContext& ctx) { return AtomicIncrement(ctx, counter); });
  EXPECT_EQ(memory.Words64(counter)[0], 100000u);
}

}  // namespace
}  // namespace hpsf::simt
