// Level 4's promise, on hand-made pairs of runs: every difference an unordered run may show passes, every
// difference the contract rules out fails, for each kind of run. Deterministic, unlike the races that produce
// such differences for real (property_tests/crosscheck_repeat_test.cpp runs those).
#include "verifier/contract/rerun_check.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/hash_table.h"

namespace hpsf {
namespace {

// Two records of one cell placed in slot 1 of a 4-slot table, a third without a vertex.
HashedRun TwoRecordsInOneSlot(Accumulation accumulation) {
  HashedRun run;
  run.table.capacity = 4;
  run.table.probe_limit = 4;
  run.table.accumulation = accumulation;
  run.table.tags = {0, 7, 0, 0};
  run.table.counts = {0, 2, 0, 0};
  run.table.fixed_sums = {{0, 0, 0}, {10, 20, 30}, {0, 0, 0}, {0, 0, 0}};
  run.table.float_sums = {{0, 0, 0}, {1.0f, 2.0f, 3.0f}, {0, 0, 0}, {0, 0, 0}};
  run.placements = {1, 1, kNotPlaced};
  run.image = Image(2, 1);
  run.image.pixels = {glm::vec3(0.5f), glm::vec3(0.25f)};
  return run;
}

// The same cell claimed slot 2 instead: another order of claims.
HashedRun MovedToSlot2(HashedRun run) {
  std::swap(run.table.tags[1], run.table.tags[2]);
  std::swap(run.table.counts[1], run.table.counts[2]);
  std::swap(run.table.fixed_sums[1], run.table.fixed_sums[2]);
  std::swap(run.table.float_sums[1], run.table.float_sums[2]);
  run.placements = {2, 2, kNotPlaced};
  return run;
}

bool Keeps(const HashedRun& a, const HashedRun& b, RerunPromise promise) {
  return CompareReruns(a, b, promise).empty();
}

TEST(RerunPromise, ClassifiesByOrderAccumulationAndFailures) {
  EXPECT_EQ(RerunPromiseFor(true, Accumulation::kFloat32, true), RerunPromise::kEverything);
  EXPECT_EQ(RerunPromiseFor(false, Accumulation::kFixed64, false), RerunPromise::kCountsSumsAndImage);
  EXPECT_EQ(RerunPromiseFor(false, Accumulation::kFloat32, false), RerunPromise::kCounts);
  EXPECT_EQ(RerunPromiseFor(false, Accumulation::kFixed64, true), RerunPromise::kNothing);
  EXPECT_EQ(RerunPromiseFor(false, Accumulation::kFloat32, true), RerunPromise::kNothing);
  EXPECT_EQ(RerunPromiseFor(false, Accumulation::kFixed64, false, true), RerunPromise::kCountsAndSums);
  EXPECT_EQ(RerunPromiseFor(false, Accumulation::kFloat32, false, true), RerunPromise::kCounts);
  EXPECT_EQ(RerunPromiseFor(false, Accumulation::kFixed64, true, true), RerunPromise::kNothing);
}

TEST(RerunPromise, Float32SumsInAnotherOrderKeepAnUnorderedPromise) {
  const HashedRun first = TwoRecordsInOneSlot(Accumulation::kFloat32);
  HashedRun second = MovedToSlot2(first);
  second.table.float_sums[2][0] = std::nextafter(1.0f, 2.0f);  // the adds rounded in another order
  second.image.pixels[0].x = std::nextafter(0.5f, 1.0f);
  EXPECT_TRUE(Keeps(first, second, RerunPromise::kCounts));
  EXPECT_FALSE(Keeps(first, second, RerunPromise::kEverything)) << "an ordered run repeats its bits";
}

TEST(RerunPromise, AnotherSlotWithTheSameCountsAndSumsKeepsTheFixed64Promise) {
  const HashedRun first = TwoRecordsInOneSlot(Accumulation::kFixed64);
  EXPECT_TRUE(Keeps(first, MovedToSlot2(first), RerunPromise::kCountsSumsAndImage));
  EXPECT_FALSE(Keeps(first, MovedToSlot2(first), RerunPromise::kEverything));
  EXPECT_TRUE(Keeps(first, first, RerunPromise::kEverything));
}

TEST(RerunPromise, ALostCountBreaksEveryPromiseButNothing) {
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    const HashedRun first = TwoRecordsInOneSlot(accumulation);
    HashedRun second = MovedToSlot2(first);
    second.table.counts[2] = 1;
    for (const RerunPromise p : {RerunPromise::kEverything, RerunPromise::kCountsSumsAndImage, RerunPromise::kCounts}) {
      EXPECT_FALSE(Keeps(first, second, p)) << ToString(p);
    }
    EXPECT_TRUE(Keeps(first, second, RerunPromise::kNothing));
  }
}

TEST(RerunPromise, AChangedFixedSumOrImageBreaksTheFixed64Promise) {
  const HashedRun first = TwoRecordsInOneSlot(Accumulation::kFixed64);
  HashedRun sums = MovedToSlot2(first), image = MovedToSlot2(first);
  sums.table.fixed_sums[2][1] += 1;
  image.image.pixels[1].z = 0.0f;
  EXPECT_FALSE(Keeps(first, sums, RerunPromise::kCountsSumsAndImage));
  EXPECT_FALSE(Keeps(first, image, RerunPromise::kCountsSumsAndImage));
}

TEST(RerunPromise, ARecordPlacedInOnlyOneRunBreaksThePromise) {
  const HashedRun first = TwoRecordsInOneSlot(Accumulation::kFloat32);
  HashedRun second = first;
  second.placements[1] = kProbeFailure;
  second.table.counts[1] = 1;
  const std::vector<std::string> differences = CompareReruns(first, second, RerunPromise::kCounts);
  ASSERT_EQ(differences.size(), 2u);
  EXPECT_EQ(differences[0], "record 0: its slot's count is 2 in one run (slot 1) and 1 in the other (slot 1)");
  EXPECT_EQ(differences[1], "record 1: placed in one run and not in the other");
}

}  // namespace
}  // namespace hpsf
