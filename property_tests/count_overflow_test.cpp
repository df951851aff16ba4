// Counts that cannot overflow silently (docs/design/defects.md, D12). Every count is 64 bits wide: a slot's count, the
// sums' fixed64 words, the statistics. 2^64 adds are out of any test's reach, so the overflow is constructed: the
// table a frame starts from is loaded with a count just below the limit (EmulatedFilter's previous table,
// VulkanFilter::LoadTable), and the frame's adds carry it over. The kernels report the wrap (count_wraps) and the
// table checker, which counts in 128 bits, names the slot. D12 itself, a 32-bit sample counter, is run the same
// way from a count just below 2^32, in the emulator and as a shader through --accumulate-spv: the checker catches
// it, and its image differs from the correct kernel's.

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/hashed_run.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "property_tests/grid_batch.h"
#include "property_tests/loaded_table_frames.h"
#include "property_tests/vulkan_test_devices.h"
#include "verifier/checker/table_checker.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kRecordsPerCell = 4;

// Eight cells of kRecordsPerCell records each, the same in every frame (no jitter).
RecordBatch CellBatch() {
  RecordBatch batch = GridBatch(0, 8);
  std::vector<Record> records;
  for (const Record& r : batch.records) records.insert(records.end(), kRecordsPerCell, r);
  batch.records = records;
  batch.width = std::uint32_t(records.size());
  return batch;
}

FilterConfig CellConfig() {
  FilterConfig config = GridConfig(64, 8);
  config.frames = 2;
  config.fixed_point_bits = 20;  // F fixed, so a loaded table's sums need no choice
  return config;
}

// Frame 1 from a table whose record 0 slot holds `count` (property_tests/loaded_table_frames.h).
std::vector<LoadedFrame> SecondFrames(std::uint64_t count, AccumulateKernelFn kernel, const std::string& accumulate_spv,
                                      HashTableDump& loaded) {
  return FramesFromLoadedCount(count, CellBatch(), CellConfig(), loaded, kernel, accumulate_spv);
}

std::vector<TableViolation> Check(const LoadedFrame& frame, const HashTableDump& before) {
  const RecordBatch batch = CellBatch();
  return CheckTable({frame.run.table, batch.records, frame.run.keys, frame.run.placements, &before, {}, 1});
}

// A count of 2^64 - 2 takes four adds: it wraps to 2. Every backend counts the wrap, and the checker names the slot
// as a count mismatch beyond 64 bits (and the total with it); one add short of the wrap, nothing is reported.
TEST(CountOverflow, A64BitCountThatWrapsIsReportedByEveryBackendAndNamedByTheChecker) {
  HashTableDump loaded;
  for (const LoadedFrame& frame : SecondFrames(~std::uint64_t(0) - 2, AccumulateKernel, "", loaded)) {
    EXPECT_EQ(frame.run.count_wraps, 1u) << frame.name;
    const std::uint32_t slot = frame.run.placements[0];
    EXPECT_EQ(frame.run.table.counts[slot], kRecordsPerCell - 3) << frame.name;
    // The slot, and the table's total count with it.
    const std::vector<TableViolation> violations = Check(frame, loaded);
    ASSERT_FALSE(violations.empty()) << frame.name << ": the checker misses the wrap";
    EXPECT_EQ(violations[0].invariant, TableInvariant::kCountMismatch) << frame.name;
    EXPECT_EQ(violations[0].slot, slot) << frame.name;
    EXPECT_NE(violations[0].detail.find("64-bit"), std::string::npos) << violations[0].ToString();
    for (const TableViolation& v : violations) {
      EXPECT_TRUE(v.invariant == TableInvariant::kCountMismatch || v.invariant == TableInvariant::kTotalMismatch)
          << frame.name << ": " << v.ToString();
    }
  }
  for (const LoadedFrame& frame : SecondFrames(~std::uint64_t(0) - kRecordsPerCell, AccumulateKernel, "", loaded)) {
    EXPECT_EQ(frame.run.count_wraps, 0u) << frame.name;
    EXPECT_EQ(frame.run.table.counts[frame.run.placements[0]], ~std::uint64_t(0)) << frame.name;
    EXPECT_TRUE(Check(frame, loaded).empty()) << frame.name << ": " << Check(frame, loaded).front().ToString();
  }
}

// A count of 2^32 - 2: the 64-bit counter passes 2^32 with nothing to report; D12's 32-bit counter wraps to 2,
// which the checker names, and its cell's average (sum over 2) is far from the right one's, so is the image.
TEST(CountOverflow, D12A32BitCounterIsCaughtByTheCheckerAndTheImage) {
  const std::uint64_t count = (std::uint64_t(1) << 32) - 2;
  HashTableDump loaded;
  const std::vector<LoadedFrame> right = SecondFrames(count, AccumulateKernel, "", loaded);
  for (const LoadedFrame& frame : right) {
    EXPECT_EQ(frame.run.table.counts[frame.run.placements[0]], count + kRecordsPerCell) << frame.name;
    EXPECT_TRUE(Check(frame, loaded).empty()) << frame.name;
  }
  const std::vector<LoadedFrame> d12 =
      SecondFrames(count, D12Count32Bit, HPSF_SHADER_VARIANT_DIR "/accumulate_D12.spv", loaded);
  for (std::size_t b = 0; b < d12.size(); ++b) {
    const LoadedFrame& frame = d12[b];
    const std::uint32_t slot = frame.run.placements[0];
    EXPECT_EQ(frame.run.table.counts[slot], kRecordsPerCell - 2) << frame.name << ": the 32-bit counter wrapped";
    const std::vector<TableViolation> violations = Check(frame, loaded);
    ASSERT_FALSE(violations.empty()) << frame.name << ": the checker misses D12";
    EXPECT_EQ(violations[0].invariant, TableInvariant::kCountMismatch) << frame.name;
    EXPECT_EQ(violations[0].slot, slot) << frame.name;
    EXPECT_NE(frame.run.image.pixels[0], right[b].run.image.pixels[0]) << frame.name << ": the image misses D12";
  }
}

}  // namespace
}  // namespace hpsf::testing
