// packed-decimal sums (core/shared/packed_sums.h): SHaRC's four 32-bit words per slot, its sums at 1000 and its count
// packed with a frame counter, kept in range by the settle's halving rule. Every backend must give the same words
// as the reference's exact map, frame after frame, halvings included; and what the layout cannot hold (a sum past
// 32 bits within one frame, a count past 24) must be counted by the backends and named by the table checker, never
// hidden. Cells are constructed (one record repeated), so each figure below is worked by hand.

#include "core/shared/packed_sums.h"

#include <array>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/hashed_run.h"
#include "core/temporal.h"
#include "emulated/emulated_filter.h"
#include "property_tests/grid_batch.h"
#include "property_tests/hashed_backends.h"
#include "property_tests/loaded_table_frames.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_backend.h"
#include "verifier/checker/table_checker.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf::testing {
namespace {

// Two cells: `bright` records of contribution `value` in cell A (record 0 on), four of 0.5 in cell B after them.
RecordBatch TwoCells(std::uint32_t bright, float value) {
  const RecordBatch grid = GridBatch(0, 2);
  Record a = grid.records[0];
  a.contribution = glm::vec4(value, value, value, a.contribution.w);
  RecordBatch batch = grid;
  batch.records.assign(bright, a);
  batch.records.insert(batch.records.end(), 4, grid.records[1]);
  batch.width = std::uint32_t(batch.records.size());
  return batch;
}

FilterConfig PackedConfig(std::uint32_t frames) {
  FilterConfig config = GridConfig(64, 8);
  config.accumulation = Accumulation::kPackedDecimal;
  config.frames = frames;
  return config;
}

std::vector<TableViolation> Check(const RecordBatch& batch, const HashedRun& run, const HashTableDump* before,
                                  std::uint32_t frame) {
  return CheckTable({run.table, batch.records, run.keys, run.placements, before, {}, frame});
}

struct Words {
  std::array<std::uint64_t, 3> sums;
  std::uint64_t count;
  std::uint32_t frames;
};
Words SlotWords(const HashedRun& run, std::uint32_t record) {
  const std::uint32_t slot = run.placements[record];
  return {run.table.fixed_sums[slot], run.table.counts[slot], run.table.frame_counters[slot]};
}
Words CellWords(const FilterResult& result, std::uint32_t record) {
  const TableCell& cell = result.cells[result.placement[record]];
  return {cell.fixed_sum, cell.count, cell.frames};
}
std::string Text(const Words& w) {
  return "sums " + std::to_string(w.sums[0]) + " count " + std::to_string(w.count) + " frames " +
         std::to_string(w.frames);
}

TEST(PackedSums, TheSettleByHand) {
  using shared::SettlePacked;
  // Halving rounds a sum half to even and a count up; the frame counter advances by one and saturates.
  EXPECT_EQ(shared::HalveToEven(3u), 2u);
  EXPECT_EQ(shared::HalveToEven(5u), 2u);
  EXPECT_EQ(shared::HalveToEven(1u), 0u);
  EXPECT_EQ(shared::HalveToEven(0xFFFFFFFFu), 0x80000000u);
  EXPECT_EQ(shared::HalveUp(1u), 1u);
  EXPECT_EQ(shared::HalveUp(0x100001u), 0x80001u);
  // Below both bounds: only the frame counter moves.
  EXPECT_EQ(SettlePacked(glm::uvec4(7u, 8u, 9u, shared::PackCountWord(3u, 4u))),
            glm::uvec4(7u, 8u, 9u, shared::PackCountWord(3u, 5u)));
  EXPECT_EQ(SettlePacked(glm::uvec4(7u, 8u, 9u, shared::PackCountWord(3u, 255u))),
            glm::uvec4(7u, 8u, 9u, shared::PackCountWord(3u, 255u)));
  // A count above 2^20, or a sum at 2^31: all four halve.
  EXPECT_EQ(SettlePacked(glm::uvec4(5u, 6u, 7u, shared::PackCountWord(0x100001u, 0u))),
            glm::uvec4(2u, 3u, 4u, shared::PackCountWord(0x80001u, 1u)));
  EXPECT_EQ(SettlePacked(glm::uvec4(5u, 0x80000000u, 7u, shared::PackCountWord(1u, 9u))),
            glm::uvec4(2u, 0x40000000u, 4u, shared::PackCountWord(1u, 10u)));
  EXPECT_EQ(SettlePacked(glm::uvec4(5u, 0x7FFFFFFFu, 7u, shared::PackCountWord(0x100000u, 9u))),
            glm::uvec4(5u, 0x7FFFFFFFu, 7u, shared::PackCountWord(0x100000u, 10u)));
  // No samples, no settle: an empty slot and a tombstone stay all zero.
  EXPECT_EQ(SettlePacked(glm::uvec4(0u)), glm::uvec4(0u));
}

// Cell A takes 6000 records of 400 a frame: 400 x 1000 x 6000 = 2.4e9 per channel, past 2^31, so the settle halves it
// every frame; cell B's four records of 0.5 (500 each) never are. Worked by hand, frame by frame:
//   frame 0: A 2.4e9 / 6000 halve to 1.2e9 / 3000;  frame 1: 3.6e9 / 9000 to 1.8e9 / 4500;
//   frame 2: 4.2e9 / 10500 to 2.1e9 / 5250 (4.2e9 still below 2^32);  B: 2000 / 4, 4000 / 8, 6000 / 12.
// Every backend (the emulator fast and faithful, Vulkan mapped and staged) gives those words, equal to the
// reference's, and the checker holds each frame to the settle of the frame before.
TEST(PackedSums, EveryBackendHalvesACellToTheWordsWorkedByHand) {
  const RecordBatch batch = TwoCells(6000, 400.0f);
  FilterConfig config = PackedConfig(3);
  const std::uint64_t a_sums[] = {1200000000, 1800000000, 2100000000};
  const std::uint64_t a_counts[] = {3000, 4500, 5250};
  ReferenceBackend reference;
  std::vector<HashedBackend> hashed = HashedBackends();
  std::vector<HashTableDump> before(hashed.size());
  for (std::uint32_t frame = 0; frame < 3; ++frame) {
    config.frame = frame;
    reference.FilterFrame(batch, config);
    const Words a{{a_sums[frame], a_sums[frame], a_sums[frame]}, a_counts[frame], frame + 1};
    const Words b{{2000u * (frame + 1), 2000u * (frame + 1), 2000u * (frame + 1)}, 4u * (frame + 1), frame + 1};
    const FilterResult& exact = *reference.LastExactResult();
    EXPECT_EQ(Text(CellWords(exact, 0)), Text(a)) << "reference, frame " << frame;
    EXPECT_EQ(Text(CellWords(exact, 6000)), Text(b)) << "reference, frame " << frame;
    EXPECT_EQ(exact.stats.cells_halved, 1u) << "reference, frame " << frame;
    for (std::size_t k = 0; k < hashed.size(); ++k) {
      const std::string who = hashed[k].name + ", frame " + std::to_string(frame);
      hashed[k].backend->FilterFrame(batch, config);
      const HashedRun& run = RunOf(*hashed[k].backend);
      EXPECT_EQ(Text(SlotWords(run, 0)), Text(a)) << who;
      EXPECT_EQ(Text(SlotWords(run, 6000)), Text(b)) << who;
      EXPECT_EQ(run.halved, 1u) << who;
      EXPECT_EQ(run.wraps, 0u) << who;
      const std::vector<TableViolation> violations = Check(batch, run, frame ? &before[k] : nullptr, frame);
      EXPECT_TRUE(violations.empty()) << who << ": " << violations.front().ToString();
      EXPECT_EQ(run.image.pixels, exact.image.pixels) << who;
      before[k] = run.table;
    }
  }
}

// ema:0.25 over packed-decimal words: the blend of a cell's words before the frame with the frame's adds, then the
// settle. Cell A takes 6000 records of 400 in frame 0, then 6000 of 100 a frame; cell B four of 0.5 every frame.
// Worked by hand (alpha = min(0.25, N / (N + n)), count ceil(n / 0.75), sum average x count):
//   frame 0: A 2.4e9 / 6000 halve to 1.2e9 / 3000 (nothing to blend);  B 2000 / 4.
//   frame 1: A adds 6e8 / 6000: 0.25 x 400000 + 0.75 x 100000 = 175000 over 8000, 1.4e9 (below 2^31: no halving);
//            B 0.25 x 500 + 0.75 x 500 over 6: 3000 / 6.
//   frame 2: A 0.25 x 175000 + 0.75 x 100000 = 118750 over 8000, 9.5e8;  B again 3000 / 6.
// Every backend gives those words, equal to the reference's, and the checker holds each frame to the blend and
// settle of the frame before; held to integration instead, frame 1's cells are named.
TEST(PackedSums, EveryBackendBlendsACellToTheWordsWorkedByHand) {
  const RecordBatch bright = TwoCells(6000, 400.0f), dim = TwoCells(6000, 100.0f);
  FilterConfig config = PackedConfig(3);
  config.temporal = ParseTemporal("ema:0.25");
  const std::uint64_t a_sums[] = {1200000000, 1400000000, 950000000};
  const std::uint64_t a_counts[] = {3000, 8000, 8000};
  const std::uint64_t b_sums[] = {2000, 3000, 3000};
  const std::uint64_t b_counts[] = {4, 6, 6};
  ReferenceBackend reference;
  std::vector<HashedBackend> hashed = HashedBackends();
  std::vector<HashTableDump> before(hashed.size());
  for (std::uint32_t frame = 0; frame < 3; ++frame) {
    config.frame = frame;
    const RecordBatch& batch = frame == 0 ? bright : dim;
    reference.FilterFrame(batch, config);
    const Words a{{a_sums[frame], a_sums[frame], a_sums[frame]}, a_counts[frame], frame + 1};
    const Words b{{b_sums[frame], b_sums[frame], b_sums[frame]}, b_counts[frame], frame + 1};
    const FilterResult& exact = *reference.LastExactResult();
    EXPECT_EQ(Text(CellWords(exact, 0)), Text(a)) << "reference, frame " << frame;
    EXPECT_EQ(Text(CellWords(exact, 6000)), Text(b)) << "reference, frame " << frame;
    for (std::size_t k = 0; k < hashed.size(); ++k) {
      const std::string who = hashed[k].name + ", frame " + std::to_string(frame);
      hashed[k].backend->FilterFrame(batch, config);
      const HashedRun& run = RunOf(*hashed[k].backend);
      EXPECT_EQ(Text(SlotWords(run, 0)), Text(a)) << who;
      EXPECT_EQ(Text(SlotWords(run, 6000)), Text(b)) << who;
      EXPECT_EQ(run.halved, frame == 0 ? 1u : 0u) << who;
      const HashTableDump* previous = frame ? &before[k] : nullptr;
      const std::vector<TableViolation> violations =
          CheckTable({run.table, batch.records, run.keys, run.placements, previous, {}, frame, config.temporal});
      EXPECT_TRUE(violations.empty()) << who << ": " << violations.front().ToString();
      if (frame == 1) {  // both cells blended: held to integration, both are named (and the table's totals)
        std::set<std::uint32_t> named;
        for (const TableViolation& v : Check(batch, run, previous, frame))
          if (v.invariant == TableInvariant::kPackedSettle) named.insert(v.slot);
        EXPECT_EQ(named, (std::set<std::uint32_t>{run.placements[0], run.placements[6000]})) << who;
      }
      EXPECT_EQ(run.image.pixels, exact.image.pixels) << who;
      before[k] = run.table;
    }
  }
}

// 11000 records of 400 in one frame: 4.4e9 per channel, past 2^32 before any settle can halve it. Each channel's
// word wraps once, which every hashed backend counts (3 wraps), and the checker names it as a wrapped sum.
TEST(PackedSums, ASumThatWrapsWithinAFrameIsCountedAndNamedByTheChecker) {
  const RecordBatch batch = TwoCells(11000, 400.0f);
  const FilterConfig config = PackedConfig(1);
  for (HashedBackend& b : HashedBackends()) {
    b.backend->FilterFrame(batch, config);
    const HashedRun& run = RunOf(*b.backend);
    EXPECT_EQ(run.wraps, 3u) << b.name;
    const std::vector<TableViolation> violations = Check(batch, run, nullptr, 0);
    ASSERT_FALSE(violations.empty()) << b.name << ": the checker misses the wrap";
    EXPECT_EQ(violations[0].invariant, TableInvariant::kSumMismatch) << b.name;
    EXPECT_EQ(violations[0].slot, run.placements[0]) << b.name;
    EXPECT_NE(violations[0].detail.find("32-bit sum wrapped"), std::string::npos) << violations[0].ToString();
  }
  // 10000 records (4e9) stay below 2^32: nothing to report, and the settle halves the cell.
  const RecordBatch fits = TwoCells(10000, 400.0f);
  for (HashedBackend& b : HashedBackends()) {
    b.backend->FilterFrame(fits, config);
    const HashedRun& run = RunOf(*b.backend);
    EXPECT_EQ(run.wraps, 0u) << b.name;
    EXPECT_EQ(Text(SlotWords(run, 0)), Text({{2000000000, 2000000000, 2000000000}, 5000, 1})) << b.name;
    EXPECT_TRUE(Check(fits, run, nullptr, 0).empty()) << b.name;
  }
}

// Frame 1 from a table whose record 0 slot holds `count` (property_tests/loaded_table_frames.h).
std::vector<LoadedFrame> FromLoadedCount(std::uint32_t count, const RecordBatch& batch, HashTableDump& loaded) {
  return FramesFromLoadedCount(count, batch, PackedConfig(2), loaded);
}

// A count of 2^20 - 1 before a frame of cell A's 2 records: 2^20 + 1 passes the bound, so the settle halves it up to
// 2^19 + 1, and the sums with it (1000 + 1000 per channel, the records being 500 each: 1000). The frame counter was
// 1 after frame 0: 2 now.
TEST(PackedSums, ACountPastTwoToTheTwentyHalvesOnEveryBackend) {
  const RecordBatch batch = TwoCells(2, 0.5f);  // cell A: two records of 500 a frame
  HashTableDump loaded;
  for (const LoadedFrame& frame : FromLoadedCount((1u << 20) - 1, batch, loaded)) {
    EXPECT_EQ(Text(SlotWords(frame.run, 0)), Text({{1000, 1000, 1000}, (1u << 19) + 1, 2})) << frame.name;
    EXPECT_EQ(frame.run.halved, 1u) << frame.name;
    const std::vector<TableViolation> violations = Check(batch, frame.run, &loaded, 1);
    EXPECT_TRUE(violations.empty()) << frame.name << ": " << violations.front().ToString();
  }
}

// A count of 2^24 - 1 takes the frame's first add past the count's 24 bits: the carry lands in the frame counter.
// Every backend counts the wrap and the checker names the slot.
TEST(PackedSums, ACountThatCarriesIntoTheFrameCounterIsCountedAndNamed) {
  const RecordBatch batch = TwoCells(2, 0.5f);
  HashTableDump loaded;
  for (const LoadedFrame& frame : FromLoadedCount(shared::kPackedCountMask, batch, loaded)) {
    EXPECT_EQ(frame.run.count_wraps, 1u) << frame.name;
    const std::vector<TableViolation> violations = Check(batch, frame.run, &loaded, 1);
    ASSERT_FALSE(violations.empty()) << frame.name << ": the checker misses the carry";
    EXPECT_EQ(violations[0].invariant, TableInvariant::kCountMismatch) << frame.name;
    EXPECT_EQ(violations[0].slot, frame.run.placements[0]) << frame.name;
    EXPECT_NE(violations[0].detail.find("24-bit"), std::string::npos) << violations[0].ToString();
  }
}

// The checker's settle is fed: a slot whose frame counter, count or sums differ from the settle of its exact words
// by one is named, as a broken settle pass would leave it (a counter not advanced, a count or a sum rounded the
// other way).
TEST(PackedSums, TheCheckerNamesASlotThatIsNotTheSettleOfItsExactWords) {
  const RecordBatch batch = TwoCells(6000, 400.0f);
  const EmulatedRun right = EmulatedFilter(batch, PackedConfig(1), EmulatorOptions{});
  ASSERT_TRUE(Check(batch, right, nullptr, 0).empty());
  const std::uint32_t a = right.placements[0], b = right.placements[6000];
  const auto broken = [&](auto&& change) {
    HashedRun run = right;
    change(run.table);
    return Check(batch, run, nullptr, 0);
  };
  const std::vector<std::vector<TableViolation>> cases = {
      broken([&](HashTableDump& t) { t.frame_counters[b] = 0; }),   // the counter not advanced
      broken([&](HashTableDump& t) { t.counts[a] -= 1; }),          // a count off by one
      broken([&](HashTableDump& t) { t.fixed_sums[a][1] += 1; })};  // a sum off by one
  for (std::size_t k = 0; k < cases.size(); ++k) {
    ASSERT_FALSE(cases[k].empty()) << "case " << k;
    EXPECT_EQ(cases[k][0].invariant, TableInvariant::kPackedSettle) << cases[k][0].ToString();
  }
}

}  // namespace
}  // namespace hpsf::testing
