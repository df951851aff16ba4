// The Vulkan backend held to the contract (label vulkan; in CI on lavapipe, never skipped): on every built-in
// scene, hard cases included, in both accumulation modes, level 1 (key words, slot0, fingerprint equal core's),
// level 2 (the table checker) and level 3 (fixed64 cells and image bit-identical to the reference where
// nothing failed or aliased) hold; generated batches with tiny tables and 8-bit fingerprints pass the checker.
// Also reports how close the emulator (warp size 8, round-robin) comes to lavapipe's float32 bits.
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "emulated/emulated_filter.h"
#include "property_tests/record_generators.h"
#include "tools/checks/crosscheck.h"
#include "tools/checks/table_checker.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf::testing {
namespace {

RecordBatch Traced(const std::string& scene, std::uint32_t size, std::uint32_t spp) {
  TraceOptions trace;
  trace.width = trace.height = size;
  trace.samples_per_pixel = spp;
  return TraceRecords(LoadScene(scene), trace).batch;
}

void ExpectContract(const RecordBatch& batch, const FilterConfig& config, const std::string& what) {
  const CrosscheckReport report = Crosscheck(batch, config, {"reference", "vulkan"}, EmulatorOptions{});
  ASSERT_EQ(report.levels.size(), 4u);
  EXPECT_TRUE(report.levels[0].applicable) << what;
  for (const LevelVerdict& v : report.levels) {
    EXPECT_TRUE(!v.applicable || v.passed) << what << ": level " << v.level << " " << v.name << " failed: "
                                           << (v.failures.empty() ? v.note : v.failures.front());
  }
}

TEST(VulkanBackend, EveryBuiltInSceneHoldsTheContractInBothModes) {
  for (const std::string scene : {"cornell", "furnace", "cornell-far-1e5", "cornell-far-1e7", "cornell-tiny", "cornell-zero-red"}) {
    const RecordBatch batch = Traced(scene, 32, 2);
    for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
      FilterConfig config;
      config.capacity = 1u << 14;
      config.accumulation = accumulation;
      ExpectContract(batch, config, scene + (accumulation == Accumulation::kFixed64 ? " fixed64" : " float32"));
    }
  }
}

TEST(VulkanBackend, UnkeyableRecordsAndClassifiedRecordsHoldTheContract) {
  const RecordBatch batch = Traced("cornell", 32, 2);
  FilterConfig unkeyable;  // level of detail off with a tiny cell: every vertex unkeyable
  unkeyable.lod = false;
  unkeyable.cell_size = 1e-30f;
  ExpectContract(batch, unkeyable, "unkeyable");
  FilterConfig crowded;  // probe failures and fingerprint aliases
  crowded.capacity = 64;
  crowded.probe_limit = 4;
  crowded.fingerprint_bits = 8;
  VulkanDevice device;
  VulkanFilter filter(device);
  const VulkanRun run = filter.Run(batch, crowded);
  EXPECT_GT(run.probe_failures, 0u);
  EXPECT_TRUE(CheckTable({run.table, batch.records, run.keys, run.placements}).empty());
  ExpectContract(batch, crowded, "crowded");
}

RC_GTEST_PROP(VulkanBackend, EveryTablePassesTheCheckerOnGeneratedBatches, ()) {
  static VulkanDevice device;
  static VulkanFilter filter(device);
  const std::uint32_t seed = *rc::gen::arbitrary<std::uint32_t>();
  const std::uint32_t count = *rc::gen::inRange(1u, 600u);
  RecordGenerator generator(seed);
  RecordBatch batch;
  batch.width = count;
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 0.01 * (1 + seed % 50);
  batch.records = generator.MixedBatch(KeyCase{}.Params(0), count);
  for (std::uint32_t i = 0; i < count; ++i) batch.records[i].path.x = i;
  FilterConfig config;
  config.capacity = 1u << *rc::gen::inRange(4, 11);
  config.probe_limit = *rc::gen::inRange(1u, 17u);
  config.fingerprint_bits = *rc::gen::element(8u, 16u, 32u);
  config.accumulation = *rc::gen::element(Accumulation::kFixed64, Accumulation::kFloat32);
  const VulkanRun run = filter.Run(batch, config);
  const auto violations = CheckTable({run.table, batch.records, run.keys, run.placements});
  RC_ASSERT(violations.empty());
}

// lavapipe runs a workgroup's invocations in SIMD lanes of 8 and its float atomics one lane after another; the
// emulator's warp size 8 with round-robin warps is its closest model. Report how many slot sums agree.
TEST(VulkanBackend, Float32BitsBesideTheEmulatorsSequentialOrder) {
  const RecordBatch batch = Traced("cornell", 32, 4);
  FilterConfig config;
  config.capacity = 1u << 14;
  config.accumulation = Accumulation::kFloat32;
  VulkanDevice device;
  VulkanFilter filter(device);
  const VulkanRun gpu = filter.Run(batch, config);
  EmulatorOptions options;
  options.mode = simt::Mode::kFaithful;
  options.warp_size = 8;
  options.schedule = "round-robin";
  const EmulatedRun emulated = EmulatedFilter(batch, config, options);
  std::uint64_t compared = 0, equal = 0;
  std::int64_t worst_ulps = 0;
  for (std::uint32_t s = 0; s < config.capacity; ++s) {
    if (gpu.table.counts[s] < 2) continue;  // one add: no order to compare
    ASSERT_EQ(gpu.table.counts[s], emulated.table.counts[s]) << "slot " << s;
    for (int c = 0; c < 3; ++c) {
      const std::int64_t a = std::bit_cast<std::int32_t>(gpu.table.float_sums[s][c]);
      const std::int64_t b = std::bit_cast<std::int32_t>(emulated.table.float_sums[s][c]);
      ++compared;
      equal += a == b;
      worst_ulps = std::max(worst_ulps, std::abs(a - b));
    }
  }
  std::printf("lavapipe float32 vs emulator (warp 8, round-robin): %llu of %llu multi-add slot sums bit-identical, worst %lld ulps\n",
              (unsigned long long)equal, (unsigned long long)compared, (long long)worst_ulps);
  EXPECT_GT(compared, 0u);
}

}  // namespace
}  // namespace hpsf::testing
