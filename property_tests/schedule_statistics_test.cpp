// The random and PCT schedules explore what they claim. Each H0 below is checked with Pearson's
// chi-square (cells whose expected count is below 5 pooled, as Mitsuba 3 does), the p-value from Boost.Math, and
// Sidak's correction so that the family of 14 tests holds at 0.001 (each at 7.1e-5). Fixed seeds: a verdict is a
// fixed function of the code, so CI never flakes.
//   - RandomSchedule::OrderConflict on k = 2..5 lanes gives each of the k! orders with probability 1/k!: from one
//     schedule, 2^18 conflicts per k, and through LaunchFaithful, 2^14 warps per k (one seed per launch).
//   - RandomSchedule::PickWarp: two consecutive picks among n = 2, 3, 7 ready warps are uniform over the n^2
//     pairs (uniform, and independent of the previous pick); 2^17 pairs per n.
//   - PctSchedule: the initial priorities rank n = 3, 4 warps in each of the n! orders equally (2^16 seeds);
//     depth 3's two change points are uniform and independent over the first expected_steps = 16 steps (2^16
//     seeds; the pair of steps at which PCT switches warps, 121 outcomes).
// Power, shown: every test runs biased alternatives with the same seeds and sample size, asserts the same
// statistic rejects them, and asserts the power computed from the alternative's exact cell probabilities
// (noncentral chi-square) exceeds 0.999:
//   - the naive shuffle (swap position i with any of the k, for each i; the classic Fisher-Yates mistake): its k^k
//     paths cannot split evenly over k! orders (k = 3: 4/27 or 5/27, not 1/6; noncentrality 0.0123 per draw,
//     0.0298 at k = 4, 0.0497 at k = 5). For k = 2 it is exactly uniform, so k = 2 has only the next one.
//   - lanes left in lane order once in 50 conflicts (once in 10 through the launcher: a launcher that skips the
//     schedule for some groups); noncentrality e^2 (k! - 1) per draw, 4e-4 at k = 2 and e = 1/50.
//   - PickWarp returning the first ready warp once in 50 (8e-4 per pair at n = 2), and round-robin, whose picks are
//     exactly uniform one at a time: only the pairs reject it.
//   - PCT priorities by the naive shuffle; change points drawn over expected_steps - 1 steps (an off-by-one).
// Rejection needs noncentrality about 50 at one degree of freedom (more at more). The weakest alternatives here,
// lane order once in 50 on 2 lanes and the first of 2 warps once in 50, reach 105 with the sample sizes above
// (type II error 2e-10 and 6e-9, printed by each test); the others are far beyond.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "emulated/simt/launcher.h"
#include "verifier/theory/chi_square.h"

namespace hpsf::simt {
namespace {

constexpr int kFamily = 14;
const double kAlpha = SidakLevel(0.001, kFamily);
constexpr double kMinPower = 0.999;
// Each test draws its own seeds, kSeed + a base of its own, so the 14 are independent as Sidak assumes; its
// alternatives reuse them.
constexpr std::uint32_t kSeed = 20261121;

std::size_t Factorial(std::size_t n) { return n <= 1 ? 1 : n * Factorial(n - 1); }

// Lexicographic index in [0, k!) of an order of 0 .. k-1 (its Lehmer code).
std::size_t OrderIndex(std::span<const std::uint32_t> order) {
  std::size_t index = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    std::size_t smaller_after = 0;
    for (std::size_t j = i + 1; j < order.size(); ++j) smaller_after += order[j] < order[i];
    index += smaller_after * Factorial(order.size() - 1 - i);
  }
  return index;
}

void ExpectAccepted(const std::string& what, std::span<const std::uint64_t> observed, std::span<const double> null) {
  const ChiSquare result = ChiSquareTest(observed, null);
  std::printf("  %-44s %s\n", what.c_str(), result.ToString().c_str());
  EXPECT_GT(result.p_value, kAlpha) << what << ": " << result.ToString();
}

void ExpectRejected(const std::string& what, std::span<const std::uint64_t> observed, std::span<const double> null,
                    std::span<const double> alternative) {
  const ChiSquare result = ChiSquareTest(observed, null);
  const double samples = double(std::accumulate(observed.begin(), observed.end(), std::uint64_t(0)));
  const Power power = PowerAgainst(null, alternative, samples, kAlpha);
  std::printf("  %-44s %s; noncentrality %.0f, type II error %.2g\n", what.c_str(), result.ToString().c_str(),
              power.noncentrality, 1.0 - power.power);
  EXPECT_LT(result.p_value, kAlpha) << what << " not rejected: " << result.ToString();
  EXPECT_GT(power.power, kMinPower) << what << ": noncentrality " << power.noncentrality;
}

// The helpers themselves: cells expected below 5 pool until the pool reaches 5; an outcome H0 rules out rejects.
TEST(ScheduleStatistics, ChiSquarePoolsSmallCellsAndRejectsImpossibleOutcomes) {
  const double probabilities[] = {0.5, 0.3, 0.1, 0.06, 0.04, 0.0};
  const Pooling pooling = PoolCells(probabilities, 100);  // expected 50, 30, 10, 6, 4, 0
  EXPECT_EQ(pooling.groups, 4);
  EXPECT_EQ(pooling.group_of_cell[3], pooling.group_of_cell[4]);  // 4 < 5 takes the 6
  EXPECT_NE(pooling.group_of_cell[2], pooling.group_of_cell[3]);
  EXPECT_EQ(pooling.group_of_cell[5], -1);
  const std::uint64_t exact[] = {50, 30, 10, 7, 3, 0}, impossible[] = {50, 30, 10, 6, 3, 1};
  EXPECT_EQ(ChiSquareTest(exact, probabilities).dof, 3);
  EXPECT_DOUBLE_EQ(ChiSquareTest(exact, probabilities).statistic, 0.0);
  EXPECT_EQ(ChiSquareTest(impossible, probabilities).p_value, 0.0);
}

// --- Alternatives: biased schedules drawing from the same counter RNG, with the same seeds. ---

// The classic shuffle mistake: swap each position with a uniform one among all k.
class NaiveShuffleSchedule : public RandomSchedule {
 public:
  using RandomSchedule::RandomSchedule;
  void OrderConflict(std::span<std::uint32_t> lanes) override {
    for (std::size_t i = 0; i < lanes.size(); ++i) std::swap(lanes[i], lanes[Next(std::uint32_t(lanes.size()))]);
  }
};

// Leaves a conflict in lane order once in `one_in`: a schedule or launcher that skips some groups.
class SometimesLaneOrderSchedule : public RandomSchedule {
 public:
  SometimesLaneOrderSchedule(std::uint32_t seed, std::uint32_t one_in) : RandomSchedule(seed), one_in_(one_in) {}
  void OrderConflict(std::span<std::uint32_t> lanes) override {
    if (Next(one_in_) != 0) RandomSchedule::OrderConflict(lanes);
  }

 private:
  std::uint32_t one_in_;
};

// Picks the first ready warp once in `one_in`, uniformly otherwise.
class SometimesFirstSchedule : public RandomSchedule {
 public:
  SometimesFirstSchedule(std::uint32_t seed, std::uint32_t one_in) : RandomSchedule(seed), one_in_(one_in) {}
  std::size_t PickWarp(std::span<const std::uint32_t> ready) override {
    return Next(one_in_) == 0 ? 0 : RandomSchedule::PickWarp(ready);
  }

 private:
  std::uint32_t one_in_;
};

// Exact order probabilities of the naive shuffle, from its k^k equally likely paths; `reversed` gives those of
// the reversed order (a PCT ranking: the last of the shuffled order has the highest priority).
std::vector<double> NaiveShuffleProbabilities(std::uint32_t k, bool reversed = false) {
  std::vector<double> probabilities(Factorial(k));
  const std::size_t paths = std::size_t(std::pow(k, k));
  for (std::size_t path = 0; path < paths; ++path) {
    std::vector<std::uint32_t> order(k);
    std::iota(order.begin(), order.end(), 0u);
    std::size_t digits = path;
    for (std::uint32_t i = 0; i < k; ++i, digits /= k) std::swap(order[i], order[digits % k]);
    if (reversed) std::reverse(order.begin(), order.end());
    probabilities[OrderIndex(order)] += 1.0 / double(paths);
  }
  return probabilities;
}

// Lane order (index 0) with extra probability e, uniform otherwise.
std::vector<double> LaneOrderMixture(std::uint32_t k, double e) {
  std::vector<double> probabilities(Factorial(k), (1.0 - e) / double(Factorial(k)));
  probabilities[0] += e;
  return probabilities;
}

// --- 1. Conflict orders. ---

constexpr std::uint64_t kDirectConflicts = std::uint64_t(1) << 18;

// Orders `samples` conflicts of lanes 0 .. k-1 with one schedule, as one long launch would, and counts each order.
std::vector<std::uint64_t> CountOrders(Schedule& schedule, std::uint32_t k, std::uint64_t samples) {
  std::vector<std::uint64_t> counts(Factorial(k));
  std::vector<std::uint32_t> lanes(k);
  for (std::uint64_t s = 0; s < samples; ++s) {
    std::iota(lanes.begin(), lanes.end(), 0u);
    schedule.OrderConflict(lanes);
    ++counts[OrderIndex(lanes)];
  }
  return counts;
}

TEST(ScheduleStatistics, RandomOrderConflictGivesEachOrderOfKLanesEqually) {
  for (std::uint32_t k = 2; k <= 5; ++k) {
    const std::vector<double> uniform(Factorial(k), 1.0 / double(Factorial(k)));
    const std::string lanes = "k = " + std::to_string(k) + ": ";
    RandomSchedule real(kSeed + k);
    ExpectAccepted(lanes + "random", CountOrders(real, k, kDirectConflicts), uniform);
    SometimesLaneOrderSchedule lazy(kSeed + k, 50);
    ExpectRejected(lanes + "lane order once in 50", CountOrders(lazy, k, kDirectConflicts), uniform,
                   LaneOrderMixture(k, 1.0 / 50));
    if (k == 2) continue;  // the naive shuffle is exactly uniform on 2 lanes
    NaiveShuffleSchedule naive(kSeed + k);
    ExpectRejected(lanes + "naive shuffle", CountOrders(naive, k, kDirectConflicts), uniform,
                   NaiveShuffleProbabilities(k));
  }
}

constexpr std::uint32_t kWarpsPerLaunch = 128;
constexpr std::uint32_t kLaunches = 128;  // 2^14 conflicts per k

// Each lane adds 1 to its warp's counter (the warp's k adds conflict) and stores the old value: its place in the
// order the launcher applied.
KernelTask RecordPlace(ThreadContext& ctx, std::uint32_t counters, std::uint32_t places, std::uint32_t k) {
  const std::uint64_t place = co_await ctx.AtomicAdd(counters, ctx.Thread() / k, 1);
  co_await ctx.Store(places, ctx.Thread(), place);
}

using ScheduleFactory = std::function<std::unique_ptr<Schedule>(std::uint32_t seed)>;

template <typename Policy, typename... Arguments>
ScheduleFactory Factory(Arguments... arguments) {
  return [=](std::uint32_t seed) { return std::make_unique<Policy>(seed, arguments...); };
}

// Applied orders of warps of k lanes over kLaunches launches, each with a schedule of its own seed (as --schedule
// random:SEED makes one per launch).
std::vector<std::uint64_t> CountAppliedOrders(std::uint32_t k, const ScheduleFactory& make) {
  std::vector<std::uint64_t> counts(Factorial(k));
  std::vector<std::uint32_t> order(k);
  for (std::uint32_t launch = 0; launch < kLaunches; ++launch) {
    DeviceMemory memory;
    const std::uint32_t counters = memory.Allocate32("counters", kWarpsPerLaunch);
    const std::uint32_t places = memory.Allocate32("places", std::size_t(k) * kWarpsPerLaunch);
    const std::unique_ptr<Schedule> schedule = make(kSeed + (1u << 10) * k + launch);
    LaunchFaithful(
        memory, k * kWarpsPerLaunch, k, [&](ThreadContext& ctx) { return RecordPlace(ctx, counters, places, k); },
        *schedule);
    for (std::uint32_t warp = 0; warp < kWarpsPerLaunch; ++warp) {
      EXPECT_EQ(memory.Words32(counters)[warp], k);
      for (std::uint32_t lane = 0; lane < k; ++lane) order[memory.Words32(places)[warp * k + lane]] = lane;
      ++counts[OrderIndex(order)];
    }
  }
  return counts;
}

TEST(ScheduleStatistics, RandomConflictOrdersAppliedByTheLauncherAreUniform) {
  for (std::uint32_t k = 2; k <= 5; ++k) {
    const std::vector<double> uniform(Factorial(k), 1.0 / double(Factorial(k)));
    const std::string lanes = "launched, k = " + std::to_string(k) + ": ";
    ExpectAccepted(lanes + "random", CountAppliedOrders(k, Factory<RandomSchedule>()), uniform);
    ExpectRejected(lanes + "lane order once in 10", CountAppliedOrders(k, Factory<SometimesLaneOrderSchedule>(10u)),
                   uniform, LaneOrderMixture(k, 1.0 / 10));
    if (k == 2) continue;  // the naive shuffle is exactly uniform on 2 lanes
    ExpectRejected(lanes + "naive shuffle", CountAppliedOrders(k, Factory<NaiveShuffleSchedule>()), uniform,
                   NaiveShuffleProbabilities(k));
  }
}

// --- 2. Warp picks. ---

constexpr std::uint64_t kPickPairs = std::uint64_t(1) << 17;

// Non-overlapping pairs of consecutive picks among n ready warps, cell first * n + second. The warp ids are spread
// out: PickWarp returns an index into `ready`, not an id.
std::vector<std::uint64_t> CountPickPairs(Schedule& schedule, std::uint32_t n) {
  std::vector<std::uint32_t> ready(n);
  for (std::uint32_t i = 0; i < n; ++i) ready[i] = 3 * i + 1;
  std::vector<std::uint64_t> counts(std::size_t(n) * n);
  for (std::uint64_t s = 0; s < kPickPairs; ++s) {
    const std::size_t first = schedule.PickWarp(ready), second = schedule.PickWarp(ready);
    if (first >= n || second >= n) {
      ADD_FAILURE() << "PickWarp returned " << first << ", " << second << " of " << n;
      break;
    }
    ++counts[first * n + second];
  }
  return counts;
}

TEST(ScheduleStatistics, RandomPickWarpIsUniformAndIndependentOfThePreviousPick) {
  for (std::uint32_t n : {2u, 3u, 7u}) {
    const std::vector<double> uniform(std::size_t(n) * n, 1.0 / double(n * n));
    const std::string warps = "n = " + std::to_string(n) + " ready: ";
    RandomSchedule real(kSeed + (1u << 16) + n);
    ExpectAccepted(warps + "random", CountPickPairs(real, n), uniform);

    SometimesFirstSchedule sticky(kSeed + (1u << 16) + n, 50);
    std::vector<double> single(n, (1.0 - 1.0 / 50) / n), pairs(std::size_t(n) * n);
    single[0] += 1.0 / 50;
    for (std::uint32_t a = 0; a < n; ++a) {
      for (std::uint32_t b = 0; b < n; ++b) pairs[a * n + b] = single[a] * single[b];
    }
    ExpectRejected(warps + "first warp once in 50", CountPickPairs(sticky, n), uniform, pairs);

    // Round-robin visits the warps cyclically: pairs (2j, 2j + 1) mod n, one pair per two picks.
    RoundRobinSchedule cyclic;
    std::vector<double> cyclic_pairs(std::size_t(n) * n);
    for (std::uint32_t j = 0; j < n; ++j) cyclic_pairs[(2 * j) % n * n + (2 * j + 1) % n] += 1.0 / n;
    ExpectRejected(warps + "round-robin", CountPickPairs(cyclic, n), uniform, cyclic_pairs);
  }
}

// --- 3. PCT. ---

constexpr std::uint32_t kPctSeeds = 1u << 16;

// The order in which a PCT schedule of depth 1 (no change points) runs n warps if each finishes when it runs: its
// priorities from the highest down.
std::vector<std::uint32_t> PctRanking(std::uint32_t seed, std::uint32_t n) {
  PctSchedule pct(seed, 1, n, 1);
  std::vector<std::uint32_t> ready(n), ranking;
  std::iota(ready.begin(), ready.end(), 0u);
  while (!ready.empty()) {
    const std::size_t pick = pct.PickWarp(ready);
    ranking.push_back(ready[pick]);
    ready.erase(ready.begin() + std::ptrdiff_t(pick));
  }
  return ranking;
}

TEST(ScheduleStatistics, PctInitialPrioritiesRankTheWarpsUniformly) {
  for (std::uint32_t n : {3u, 4u}) {
    const std::vector<double> uniform(Factorial(n), 1.0 / double(Factorial(n)));
    std::vector<std::uint64_t> real(Factorial(n)), naive(Factorial(n));
    for (std::uint32_t s = 0; s < kPctSeeds; ++s) {
      const std::uint32_t seed = kSeed + (n << 20) + s;
      ++real[OrderIndex(PctRanking(seed, n))];
      // The alternative: PctSchedule's construction with the naive shuffle (priority i to order[i]).
      NaiveShuffleSchedule shuffle(seed);
      std::vector<std::uint32_t> order(n);
      std::iota(order.begin(), order.end(), 0u);
      shuffle.OrderConflict(order);
      std::reverse(order.begin(), order.end());
      ++naive[OrderIndex(order)];
    }
    const std::string warps = "PCT ranking of " + std::to_string(n) + " warps: ";
    ExpectAccepted(warps + "pct", real, uniform);
    ExpectRejected(warps + "naive shuffle", naive, uniform, NaiveShuffleProbabilities(n, true));
  }
}

constexpr std::uint32_t kExpectedSteps = 16;

// Cell of the switch steps seen: (first - 1) * E + last - 1, with first = last for a single switch and 1 for none.
std::size_t SwitchCell(std::uint32_t first, std::uint32_t last) { return (first - 1) * kExpectedSteps + last - 1; }

// A PCT schedule of depth 3 over 3 always-ready warps, run for E = kExpectedSteps steps: the steps (from 1) at which
// it switches warps. Its two change points c1, c2 are steps 1 .. E ([0, E) counted from 0); each demotes the warp
// running then, so it switches at both, once when they share a step, and one at step 1 acts before the first
// pick, unseen. The observer does not know the initial ranking, so which change point is which cannot be seen;
// the pair of switch steps can. E * E: a number of switches PCT cannot make.
std::size_t ChangePointCell(std::uint32_t seed, std::uint64_t expected_steps) {
  PctSchedule pct(seed, 3, 3, expected_steps);
  const std::uint32_t ready[] = {0, 1, 2};
  std::vector<std::uint32_t> switches;
  std::size_t running = pct.PickWarp(ready);
  for (std::uint32_t step = 2; step <= kExpectedSteps; ++step) {
    const std::size_t pick = pct.PickWarp(ready);
    if (pick != running) switches.push_back(step);
    running = pick;
  }
  if (switches.empty()) return SwitchCell(1, 1);
  if (switches.size() > 2) return kExpectedSteps * kExpectedSteps;
  return SwitchCell(switches.front(), switches.back());
}

// Cell probabilities when c1, c2 are independent and uniform on the first `range` steps: each of the range^2
// pairs, mapped to the switches it shows.
std::vector<double> ChangePointProbabilities(std::uint32_t range) {
  std::vector<double> probabilities(kExpectedSteps * kExpectedSteps + 1);
  for (std::uint32_t c1 = 1; c1 <= range; ++c1) {
    for (std::uint32_t c2 = 1; c2 <= range; ++c2) {
      const std::uint32_t low = std::min(c1, c2), high = std::max(c1, c2);
      const std::size_t cell = low == 1 || low == high ? SwitchCell(high, high) : SwitchCell(low, high);
      probabilities[cell] += 1.0 / double(range * range);
    }
  }
  return probabilities;
}

TEST(ScheduleStatistics, PctChangePointsAreUniformAndIndependentOverTheExpectedSteps) {
  std::vector<std::uint64_t> real(kExpectedSteps * kExpectedSteps + 1), short_range(real.size());
  for (std::uint32_t s = 0; s < kPctSeeds; ++s) {
    ++real[ChangePointCell(kSeed + (1u << 24) + s, kExpectedSteps)];
    ++short_range[ChangePointCell(kSeed + (1u << 24) + s, kExpectedSteps - 1)];  // the off-by-one: one step short
  }
  const std::vector<double> uniform = ChangePointProbabilities(kExpectedSteps);
  ExpectAccepted("PCT change points: pct", real, uniform);
  ExpectRejected("PCT change points: one step short", short_range, uniform,
                 ChangePointProbabilities(kExpectedSteps - 1));
}

}  // namespace
}  // namespace hpsf::simt
