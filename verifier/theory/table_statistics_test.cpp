// `hpsf stats`'s figures: within their theory for the key path's own keys, a warning when an index hash clusters
// (probe failures above the theory); the distinct keys and records per cell counted.
#include "verifier/theory/table_statistics.h"

#include <cstdio>

#include <gtest/gtest.h>

#include "core/key_batch.h"

namespace hpsf {
namespace {

// 12,000 records in 3,000 distinct cells of a unit grid, four records each, into 4,096 slots.
struct GridKeys {
  GridKeys() {
    config.lod = false;
    config.cell_size = 1.0f;
    config.normal.mode = NormalMode::kNone;
    config.capacity = 4096;
    config.probe_limit = 16;
    for (std::uint32_t i = 0; i < 12000; ++i) {
      VertexSample v;
      v.pixel = i;
      const std::uint32_t cell = i % 3000;
      v.position = glm::vec3(float(cell % 64), float(cell / 64), 0.0f) + 0.5f;
      v.previous = v.position - glm::vec3(0.0f, 0.0f, 1.0f);
      v.contribution = v.throughput = glm::vec3(0.5f);
      records.push_back(MakeVertexRecord(v));
    }
    config.jitter_scale = 0.0f;  // so each record stays in its cell
    keys = ComputeKeys(records, MakeKeyParams(config, 1.0f, std::uint32_t(records.size())));
  }
  FilterConfig config;
  std::vector<Record> records;
  std::vector<KeyResult> keys;
};

TEST(TableStatistics, TheKeyPathsKeysAreWithinTheory) {
  const GridKeys grid;
  const TableStatistics s = MeasureTableStatistics(grid.records, grid.keys, grid.config);
  EXPECT_EQ(s.distinct_keys, 3000u);
  EXPECT_EQ(s.max_records_per_cell, 4u);
  ASSERT_EQ(s.records_per_cell.size(), 3u);
  EXPECT_EQ(s.records_per_cell[2], 3000u);  // every key has 4 records: bucket 4..7
  EXPECT_DOUBLE_EQ(s.load, 3000.0 / 4096.0);
  EXPECT_FALSE(s.ExceedsTheory()) << s.ToJson().dump(2);
  EXPECT_EQ(s.ToJson()["exceeds_theory"], false);
}

// More distinct keys than slots (3,000 into 64): a table too small is what `hpsf stats` is for, so it gets a theory,
// not an internal error. Once the fill passes the capacity every window is full; a window of the whole table then
// fails every key that overflows it, and the theory counts those fills.
TEST(TableStatistics, AnOverfullTableIsMeasuredAgainstItsTheory) {
  GridKeys grid;
  grid.config.capacity = 64;
  grid.keys = ComputeKeys(grid.records, MakeKeyParams(grid.config, 1.0f, std::uint32_t(grid.records.size())));
  const TableStatistics s = MeasureTableStatistics(grid.records, grid.keys, grid.config);
  EXPECT_GT(s.load, 1.0);
  const ProbeLimitFigure& whole = s.probe_limits.back();
  ASSERT_EQ(whole.probe_limit, 64u);
  EXPECT_GT(whole.failures.theory, 0.97);  // the fills past 64 keys: all but the first 2%
  EXPECT_FALSE(whole.failures.ExceedsTheory()) << s.ToJson().dump(2);
}

TEST(TableStatistics, WarnsWhenProbeFailuresExceedTheTheory) {
  GridKeys grid;
  for (KeyResult& k : grid.keys) k.slot0 = k.slot0 & ~0xFu;  // an index hash that drops its low 4 bits
  const TableStatistics s = MeasureTableStatistics(grid.records, grid.keys, grid.config);
  EXPECT_TRUE(s.ExceedsTheory());
  bool failures_exceed = false;
  for (const ProbeLimitFigure& f : s.probe_limits) failures_exceed = failures_exceed || f.failures.ExceedsTheory();
  EXPECT_TRUE(failures_exceed) << s.ToJson().dump(2);
}

// Full keys alias nothing: keys that share their identity's low word (one row of cells, whose full keys differ in
// their high words alone) fail their probes as distinct keys do, where 32-bit fingerprints equal to those low words
// would alias them and take no slot.
TEST(TableStatistics, FullKeysAreInsertedWhole) {
  GridKeys grid;
  grid.config.capacity = 1024;  // 3000 keys into 1024 slots: many fail
  FilterConfig full = grid.config;
  full.key_identity = KeyIdentity::kFull;
  std::vector<KeyResult> keys = grid.keys;
  for (KeyResult& k : keys) {
    k.slot0 &= 1023u;
    k.fingerprint = 7u;  // every key's low word alike
    k.identity_high = k.words.cell_x * 64u + k.words.cell_y + 1u;
  }
  const TableStatistics aliased = MeasureTableStatistics(grid.records, keys, grid.config);
  const TableStatistics whole = MeasureTableStatistics(grid.records, keys, full);
  ASSERT_FALSE(whole.probe_limits.empty());
  for (std::size_t i = 0; i < whole.probe_limits.size(); ++i) {
    // A key that aliases takes no slot and never fails; inserted whole, every key beyond the table's slots fails.
    EXPECT_GT(whole.probe_limits[i].failures.events, aliased.probe_limits[i].failures.events)
        << whole.probe_limits[i].probe_limit;
    EXPECT_GE(whole.probe_limits[i].failures.events, 3000u - 1024u) << whole.probe_limits[i].probe_limit;
  }
}

// murmur3's 32-bit finalizer: slot0s spread as a uniform hash would, independent of the key path's own hash.
std::uint32_t Mix(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  h *= 0xC2B2AE35u;
  return h ^ (h >> 16);
}

// The probe-failure theory is the mean over the fill (a key meets the table as full as it is when it comes), not
// the final load: for a uniform hash its bound lies inside the measured rate's interval wherever failures are
// rare enough that the failed keys it counts as inserted do not matter (limits 8 and 16 at load 0.73: measured
// 103 and 37 of 3000, theory 0.0428 and 0.0127, intervals [0.0227, 0.0494] and [0.0059, 0.0223]). At the final
// load the theory would be 0.262 and 0.121, five times the measured rates, and a hash that clusters could fail
// its keys at four times a uniform hash's rate and pass beneath it.
TEST(TableStatistics, ProbeFailureTheoryIsTheFillsMeanForAUniformHash) {
  GridKeys grid;
  for (std::size_t i = 0; i < grid.keys.size(); ++i) grid.keys[i].slot0 = Mix(std::uint32_t(i % 3000) + 1u) % 4096u;
  const TableStatistics s = MeasureTableStatistics(grid.records, grid.keys, grid.config);
  EXPECT_FALSE(s.ExceedsTheory()) << s.ToJson().dump(2);
  for (const ProbeLimitFigure& f : s.probe_limits) {
    std::printf("probe limit %u: %llu of %llu, theory %.4f, interval [%.4f, %.4f]\n", f.probe_limit,
                static_cast<unsigned long long>(f.failures.events), static_cast<unsigned long long>(f.failures.trials),
                f.failures.theory, f.failures.low, f.failures.high);
    if (f.probe_limit == 8 || f.probe_limit == 16) {
      EXPECT_GE(f.failures.theory, f.failures.low) << f.probe_limit;
      EXPECT_LE(f.failures.theory, f.failures.high) << f.probe_limit;
    }
  }
}

// A rejected jitter test is a warning like a rate above its theory (`hpsf stats` exits 1 on it), and one at the
// threshold is rejected too (p <= alpha); a p-value above it is not.
TEST(TableStatistics, ARejectedJitterTestWarns) {
  const GridKeys grid;
  TableStatistics s = MeasureTableStatistics(grid.records, grid.keys, grid.config);
  ASSERT_FALSE(s.ExceedsTheory());
  s.jitter_alpha = 0.01;
  JitterVerdict verdict;
  verdict.test = JitterTest::kMean;
  verdict.chi_square.p_value = 0.5;
  s.jitter = {verdict};
  EXPECT_FALSE(s.ExceedsTheory());
  s.jitter[0].chi_square.p_value = 0.01;
  EXPECT_TRUE(s.ExceedsTheory());
  s.jitter[0].chi_square.p_value = 1e-9;
  EXPECT_TRUE(s.ExceedsTheory());
  EXPECT_EQ(s.ToJson()["exceeds_theory"], true);
}

}  // namespace
}  // namespace hpsf
