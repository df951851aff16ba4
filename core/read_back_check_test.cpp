// ReadBackFaults on runs built word by word: a clean run passes; each word the host would use as an index or a
// size, set out of range, is named with its record or slot and what was expected; CountProbes never indexes past
// its histogram, whatever the placements.
#include "core/read_back_check.h"

#include <gtest/gtest.h>

#include "core/shared/key.h"

namespace hpsf {
namespace {

// Four records in a table of 8 slots, probe limit 2: keyed at slot0 6 placed in 7 (wrapping window 6, 7), keyed at
// slot0 7 placed in 0 (window 7, 0), a probe failure and a record without a vertex.
HashedRun CleanRun() {
  HashedRun run;
  run.table.capacity = 8;
  run.table.probe_limit = 2;
  run.table.tags.assign(8, 0);
  run.table.counts.assign(8, 0);
  run.keys.assign(4, shared::EmptyKeyResult(shared::kKeyed));
  run.keys[0].slot0 = 6;
  run.keys[1].slot0 = 7;
  run.keys[2].slot0 = 3;
  run.keys[3] = shared::EmptyKeyResult(shared::kKeyNoVertex);
  run.placements = {7, 0, kProbeFailure, kNotPlaced};
  return run;
}

std::string Faults(const HashedRun& run, std::uint32_t frame = 0) {
  std::string text;
  for (const std::string& fault : ReadBackFaults(run, frame)) text += fault + "\n";
  return text;
}

TEST(ReadBackCheck, CleanRunHasNoFault) {
  HashedRun run = CleanRun();
  EXPECT_EQ(Faults(run), "");
  FinishReadBack(run, 0, "test");
  EXPECT_EQ(run.probe_failures, 1u);
  EXPECT_EQ(run.probe_lengths, (std::vector<std::uint64_t>{0, 2}));
}

TEST(ReadBackCheck, PlacementOutOfRangeIsNamed) {
  HashedRun run = CleanRun();
  run.placements[1] = 8;
  EXPECT_EQ(Faults(run),
            "record 1: placement 8 is neither a slot below the capacity 8 nor probe failure (4294967294) "
            "nor not placed (4294967295)\n");
}

TEST(ReadBackCheck, PlacementOutsideItsWindowIsNamed) {
  HashedRun run = CleanRun();
  run.placements[0] = 0;  // slot0 6, limit 2: slots 6 and 7 only
  EXPECT_EQ(Faults(run),
            "record 0: placed in slot 0, which is not one of its candidates (linear:2 from slot0 6, capacity 8)\n");
}

TEST(ReadBackCheck, PlacementOutsideItsBucketIsNamed) {
  HashedRun run = CleanRun();
  run.table.probing = ProbeKind::kBucket;  // slot0 6, buckets of 2: slots 6 and 7 only; linear would allow 0 too
  run.placements[0] = 7;
  run.placements[1] = 6;  // slot0 7 wrapped to 0 linearly; its bucket is slots 6 and 7
  EXPECT_EQ(Faults(run), "");
  run.table.probe_limit = 4;  // the bucket of slot0 6 is now slots 4 to 7
  run.placements[0] = 4;
  EXPECT_EQ(Faults(run), "");
  run.placements[0] = 0;  // linear:4 from 6 would reach 0 by wrapping; the bucket never wraps
  EXPECT_EQ(Faults(run),
            "record 0: placed in slot 0, which is not one of its candidates (bucket:4 from slot0 6, capacity 8)\n");
}

TEST(ReadBackCheck, KeyWordsUsedAsIndicesAreChecked) {
  HashedRun run = CleanRun();
  run.keys[2].slot0 = 8;
  run.keys[3].status = 3;
  EXPECT_EQ(Faults(run),
            "record 2: slot0 8 is not below the capacity 8\n"
            "record 3: key status 3 is none of keyed (0), no vertex (1) and unkeyable (2)\n");
}

TEST(ReadBackCheck, LastSeenAfterThisFrameIsNamed) {
  HashedRun run = CleanRun();
  run.table.last_seen.assign(8, 4);
  EXPECT_EQ(Faults(run, 4), "");
  run.table.last_seen[5] = 5;
  EXPECT_EQ(Faults(run, 4), "slot 5: last seen in frame 5, after this frame 4\n");
}

TEST(ReadBackCheck, StatsCountersAboveWhatTheRunCanProduceAreNamed) {
  HashedRun run = CleanRun();  // two placed records
  run.wraps = 6;
  run.count_wraps = 2;
  run.evicted = 8;
  run.seeded = 8;
  EXPECT_EQ(Faults(run), "");
  run.wraps = 7;
  run.count_wraps = 3;
  run.evicted = 9;
  run.seeded = 9;
  EXPECT_EQ(
      Faults(run),
      "stats: fixed64 wraps 7 is more than the run can produce (6, one per channel of each placed record and level)\n"
      "stats: count wraps 3 is more than the run can produce (2, one per placed record and level)\n"
      "stats: evicted 9 is more than the run can produce (8, one per slot)\n"
      "stats: seeded 9 is more than the run can produce (8, one per slot)\n");
}

TEST(ReadBackCheck, FinishReadBackThrowsNamingTheShaderAndKeepsTheKeys) {
  HashedRun run = CleanRun();
  run.placements[0] = 0xDEADBEEFu;
  try {
    FinishReadBack(run, 0, "the accumulate shader a.spv");
    FAIL() << "no ShaderOutputError";
  } catch (const ShaderOutputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("the accumulate shader a.spv wrote invalid output: record 0: ", 0), 0u);
    EXPECT_EQ(error.faults().size(), 1u);
    EXPECT_EQ(error.keys().size(), 4u);
  }
}

TEST(ReadBackCheck, FaultsAreCappedAtTheLimit) {
  HashedRun run = CleanRun();
  run.placements.assign(4, 100);
  EXPECT_EQ(ReadBackFaults(run, 0, 3).size(), 3u);
}

TEST(CountProbes, PlacementOutsideTheWindowHasNoProbeLength) {
  HashedRun run = CleanRun();
  run.placements[0] = 2;  // distance 4 from slot0 6: past the histogram of 2 lengths
  CountProbes(run);
  EXPECT_EQ(run.probe_lengths, (std::vector<std::uint64_t>{0, 1}));
}

}  // namespace
}  // namespace hpsf
