// The shrinker: delta debugging reaches a 1-minimal batch under any predicate, keeps only the simplifications
// that still fail, leaves a kept accumulation alone and stops at its check limit.
#include "verifier/fuzzing/case_shrinker.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "core/eviction.h"
#include "core/temporal.h"
#include "verifier/fuzzing/adversarial_case.h"

namespace hpsf {
namespace {

bool HasPixel(const AdversarialCase& c, std::uint32_t pixel) {
  return std::any_of(c.batch.records.begin(), c.batch.records.end(),
                     [&](const Record& r) { return r.path.x == pixel; });
}

// A case of 96 records whose pixels are 0..95, in a float32 table with a drawn schedule.
AdversarialCase LargeCase() {
  for (std::uint64_t run = 0;; ++run) {
    AdversarialCase c = MakeAdversarialCase(11, run, {96, false, Accumulation::kFloat32});
    if (c.batch.records.size() < 60 || c.config.probe_limit < 3 || c.config.fingerprint_bits == 32 ||
        c.emulator.schedule == "round-robin" || c.family == AdversarialFamily::kKeyPath) {
      continue;
    }
    for (std::uint32_t i = 0; i < c.batch.records.size(); ++i) c.batch.records[i].path.x = i;
    return c;
  }
}

TEST(ShrinkCase, ReachesTheTwoRecordsThatFailTogetherAndTheSimplestConfig) {
  const AdversarialCase large = LargeCase();
  const auto fails = [](const AdversarialCase& c) { return HasPixel(c, 5) && HasPixel(c, 41); };
  const ShrinkResult result = ShrinkCase(large, fails);
  ASSERT_EQ(result.shrunk.batch.records.size(), 2u);
  EXPECT_EQ(result.shrunk.batch.records[0].path.x, 5u);
  EXPECT_EQ(result.shrunk.batch.records[1].path.x, 41u);
  EXPECT_EQ(result.shrunk.batch.width, 2u);
  EXPECT_EQ(result.shrunk.config.fingerprint_bits, 32u);
  EXPECT_EQ(result.shrunk.config.accumulation, Accumulation::kFixed64);
  EXPECT_EQ(result.shrunk.config.probe_limit, 1u);
  EXPECT_EQ(result.shrunk.emulator.schedule, "round-robin");
  EXPECT_EQ(result.shrunk.emulator.warp_size, 8u);
  EXPECT_FALSE(result.exhausted);
  EXPECT_LT(result.checks, 200u) << "ddmin on 2 of " << large.batch.records.size() << " records";
}

// With several filtered bounces each record carries its scattered vertex: the shrinker keeps the two in step, so the
// two records that fail keep their own scattered vertices, and a transport the failure does not need is dropped.
TEST(ShrinkCase, KeepsEachRecordsScatteredVertexWithIt) {
  AdversarialCase large = LargeCase();
  large.config.transport = true;
  for (std::uint32_t i = 0; i < large.batch.records.size(); ++i) {
    Record s = large.batch.records[(i * 7u) % large.batch.records.size()];
    s.path.y = 1000u + i;  // marks whose scattered vertex it is
    large.batch.scattered.push_back(s);
  }
  const auto fails = [](const AdversarialCase& c) {
    return c.batch.scattered.size() == c.batch.records.size() && HasPixel(c, 5) && HasPixel(c, 41);
  };
  const ShrinkResult result = ShrinkCase(large, fails);
  ASSERT_EQ(result.shrunk.batch.records.size(), 2u);
  ASSERT_EQ(result.shrunk.batch.scattered.size(), 2u);
  EXPECT_EQ(result.shrunk.batch.scattered[0].path.y, 1005u);
  EXPECT_EQ(result.shrunk.batch.scattered[1].path.y, 1041u);
  EXPECT_FALSE(result.shrunk.config.transport);
}

// A sequence of 5 frames that fails when the frame numbered 3 holds pixel 7 after a frame that holds pixel 2, under
// stale:2 eviction and an ema: the frames in between and after go, each kept frame keeps one record, the
// simplifications the failure needs stay and the others go.
TEST(ShrinkCase, ASequenceShrinksToTheFramesAndRecordsThatFail) {
  AdversarialCase c = LargeCase();
  c.config.eviction = ParseEviction("stale:2");
  c.config.temporal = ParseTemporal("ema:0.5");
  c.config.fixed_point_bits = 3;
  for (std::uint32_t k = 1; k < 5; ++k) {
    RecordBatch frame = c.batch;
    frame.frame = k;
    c.later.push_back(frame);
  }
  c.config.frames = 5;
  const auto fails = [](const AdversarialCase& a) {
    const std::vector<RecordBatch> frames = a.Frames();
    bool two = false;
    for (const RecordBatch& f : frames) {
      const bool has7 = std::any_of(f.records.begin(), f.records.end(), [](const Record& r) { return r.path.x == 7; });
      const bool has2 = std::any_of(f.records.begin(), f.records.end(), [](const Record& r) { return r.path.x == 2; });
      if (f.frame == 3 && has7 && two) return a.config.eviction.ToString() == "stale:2";
      two = two || has2;
    }
    return false;
  };
  ASSERT_TRUE(fails(c));
  const ShrinkResult result = ShrinkCase(c, fails);
  const std::vector<RecordBatch> frames = result.shrunk.Frames();
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].frame, 3u);
  ASSERT_EQ(frames[0].records.size(), 1u);
  ASSERT_EQ(frames[1].records.size(), 1u);
  EXPECT_EQ(frames[0].records[0].path.x, 2u);
  EXPECT_EQ(frames[1].records[0].path.x, 7u);
  EXPECT_EQ(frames[1].width, 1u);
  EXPECT_EQ(result.shrunk.config.frames, 2u);
  EXPECT_EQ(result.shrunk.config.eviction.ToString(), "stale:2");
  EXPECT_EQ(result.shrunk.config.temporal.ToString(), "integrate");
  EXPECT_FALSE(result.shrunk.config.fixed_point_bits.has_value());
}

TEST(ShrinkCase, TheResultIsOneMinimal) {
  // Fails while at least three records of pixels divisible by 7 remain: any three of them is a minimal answer.
  const auto fails = [](const AdversarialCase& c) {
    return std::count_if(c.batch.records.begin(), c.batch.records.end(),
                         [](const Record& r) { return r.path.x % 7 == 0; }) >= 3;
  };
  const ShrinkResult result = ShrinkCase(LargeCase(), fails);
  ASSERT_TRUE(fails(result.shrunk));
  ASSERT_EQ(result.shrunk.batch.records.size(), 3u);
  for (std::size_t i = 0; i < result.shrunk.batch.records.size(); ++i) {
    AdversarialCase without = result.shrunk;
    without.batch.records.erase(without.batch.records.begin() + std::ptrdiff_t(i));
    EXPECT_FALSE(fails(without)) << "record " << i << " was not needed";
  }
}

TEST(ShrinkCase, KeepsWhatTheFailureNeeds) {
  const AdversarialCase large = LargeCase();
  // A failure that needs the narrow fingerprint and the drawn schedule keeps both.
  const auto fails = [&](const AdversarialCase& c) {
    return c.config.fingerprint_bits == large.config.fingerprint_bits && c.emulator.schedule == large.emulator.schedule;
  };
  const ShrinkResult result = ShrinkCase(large, fails);
  EXPECT_EQ(result.shrunk.config.fingerprint_bits, large.config.fingerprint_bits);
  EXPECT_EQ(result.shrunk.emulator.schedule, large.emulator.schedule);
  EXPECT_EQ(result.shrunk.batch.records.size(), 1u);
}

TEST(ShrinkCase, LeavesAKeptAccumulationAlone) {
  const auto always = [](const AdversarialCase&) { return true; };
  EXPECT_EQ(ShrinkCase(LargeCase(), always, {.accumulation = true}).shrunk.config.accumulation, Accumulation::kFloat32);
  EXPECT_EQ(ShrinkCase(LargeCase(), always, {}).shrunk.config.accumulation, Accumulation::kFixed64);
}

TEST(ShrinkCase, LeavesAKeptProbingSchemeAlone) {
  const auto always = [](const AdversarialCase&) { return true; };
  AdversarialCase bucket = LargeCase();
  bucket.config.probing = ProbeKind::kBucket;
  bucket.config.probe_limit = 4;
  EXPECT_EQ(ShrinkCase(bucket, always, {.probing = true}).shrunk.config.probing, ProbeKind::kBucket);
  EXPECT_EQ(ShrinkCase(bucket, always, {}).shrunk.config.probing, ProbeKind::kLinear);
}

TEST(ShrinkCase, StopsAtTheCheckLimit) {
  const AdversarialCase large = LargeCase();
  const auto fails = [](const AdversarialCase& c) { return HasPixel(c, 5) && HasPixel(c, 41); };
  const ShrinkResult result = ShrinkCase(large, fails, {}, 3);
  EXPECT_TRUE(result.exhausted);
  EXPECT_EQ(result.checks, 3u);
  EXPECT_TRUE(fails(result.shrunk)) << "whatever the limit, the result still fails";
}

}  // namespace
}  // namespace hpsf
