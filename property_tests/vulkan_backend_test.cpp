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

#include "core/hash_table.h"
#include "emulated/emulated_filter.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/crosscheck.h"
#include "verifier/contract/rerun_check.h"
#include "verifier/generators/record_generators.h"

namespace hpsf::testing {
namespace {

// The contract with the host mapping the kernels' buffers and with staging copies.
void ExpectContract(const RecordBatch& batch, const FilterConfig& config, const std::string& what) {
  for (const StagingPolicy staging : kStagingPolicies) {
    VulkanBackendOptions vulkan;
    vulkan.staging = staging;
    const CrosscheckReport report =
        Crosscheck(batch, config, {"reference", "vulkan"}, EmulatorOptions{}, Defect::kNone, vulkan);
    ASSERT_EQ(report.levels.size(), 4u);
    EXPECT_TRUE(report.levels[0].applicable) << what;
    for (const LevelVerdict& v : report.levels) {
      EXPECT_TRUE(!v.applicable || v.passed)
          << what << ", --vk-staging " << ToString(staging) << ": level " << v.level << " " << v.name
          << " failed: " << (v.failures.empty() ? v.note : v.failures.front());
    }
  }
}

TEST(VulkanBackend, EveryBuiltInSceneHoldsTheContractInBothModes) {
  for (const std::string scene :
       {"cornell", "furnace", "cornell-far-1e5", "cornell-far-1e7", "cornell-tiny", "cornell-zero-red"}) {
    const RecordBatch batch = TracedBatch(scene, 32, 2);
    for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
      FilterConfig config;
      config.capacity = 1u << 14;
      config.accumulation = accumulation;
      ExpectContract(batch, config, scene + (accumulation == Accumulation::kFixed64 ? " fixed64" : " float32"));
    }
  }
}

TEST(VulkanBackend, UnkeyableRecordsAndClassifiedRecordsHoldTheContract) {
  const RecordBatch batch = TracedBatch("cornell", 32, 2);
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
  const StagingPolicy staging = *rc::gen::element(kStagingPolicies[0], kStagingPolicies[1]);
  VulkanFilter& filter = TestFilter(staging);
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

// The staging path moves the same bytes as the mapped one. With one lavapipe worker thread the order of atomics
// is fixed, so tables, placements, keys and images are bit-identical between the two; on other devices the
// order differs from run to run and the two are held to the cross-check's rerun promise instead.
TEST(VulkanBackend, StagedAndMappedRunsGiveTheSameBits) {
  const RecordBatch batch = TracedBatch("cornell", 48, 4);
  const char* previous = std::getenv("LP_NUM_THREADS");
  const std::string saved = previous ? previous : "";
  setenv("LP_NUM_THREADS", "1", 1);  // read when lavapipe creates its device
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    FilterConfig config;
    config.capacity = 1u << 13;  // load 0.6 at 16-slot windows: claims race and some windows fill
    config.accumulation = accumulation;
    VulkanDevice mapped_device("", StagingPolicy::kNever), staged_device("", StagingPolicy::kAlways);
    ASSERT_FALSE(mapped_device.info().staged);
    ASSERT_TRUE(staged_device.info().staged);
    VulkanFilter mapped_filter(mapped_device), staged_filter(staged_device);
    const VulkanRun mapped = mapped_filter.Run(batch, config), staged = staged_filter.Run(batch, config);
    EXPECT_GT(staged.timings.upload_bytes, batch.records.size() * sizeof(Record));
    EXPECT_EQ(staged.timings.upload_bytes, mapped.timings.upload_bytes);
    EXPECT_EQ(staged.timings.read_back_bytes, mapped.timings.read_back_bytes);
    EXPECT_EQ(mapped.timings.upload_copy_ms + mapped.timings.read_back_copy_ms, 0.0)
        << "a mapped run copies nothing on the device";
    const bool ordered = mapped_device.info().driver_name == "llvmpipe";
    const RerunPromise promise =
        RerunPromiseFor(ordered, accumulation, mapped.probe_failures + staged.probe_failures > 0);
    for (const std::string& difference : CompareReruns(mapped, staged, promise))
      ADD_FAILURE() << "staged against mapped: " << difference;
    if (ordered) {
      EXPECT_EQ(mapped.keys.size(), staged.keys.size());
      for (std::size_t i = 0; i < mapped.keys.size(); ++i) {
        ASSERT_EQ(KeyResultWords(mapped.keys[i]), KeyResultWords(staged.keys[i])) << "record " << i;
      }
      EXPECT_EQ(mapped.wraps, staged.wraps);
    }
  }
  if (previous) {
    setenv("LP_NUM_THREADS", saved.c_str(), 1);
  } else {
    unsetenv("LP_NUM_THREADS");
  }
}

// Float32 sums depend on the order of the atomic adds. lavapipe runs a subgroup's 8 lanes in SIMD and spreads
// workgroups over LP_NUM_THREADS worker threads (default: one per core); the emulator's closest model is warp
// size 8 with round-robin warps. Compares slot sums with both, matching slots through a record they hold
// (which slot a key claims depends on who wins a race for it).
struct Float32Agreement {
  std::uint64_t compared = 0, equal = 0, unmatched = 0;
  std::int64_t worst_ulps = 0;
};

Float32Agreement CompareFloat32WithEmulator(const RecordBatch& batch, const FilterConfig& config,
                                            std::string& device_name) {
  VulkanDevice device;
  device_name = device.info().driver_name;
  VulkanFilter filter(device);
  const VulkanRun gpu = filter.Run(batch, config);
  EmulatorOptions options;
  options.mode = simt::Mode::kFaithful;
  options.warp_size = 8;
  options.schedule = "round-robin";
  const EmulatedRun emulated = EmulatedFilter(batch, config, options);
  std::vector<std::uint32_t> record_in_slot(config.capacity, kNotPlaced);
  for (std::uint32_t i = 0; i < gpu.placements.size(); ++i) {
    if (gpu.placements[i] < config.capacity) record_in_slot[gpu.placements[i]] = i;
  }
  Float32Agreement a;
  for (std::uint32_t s = 0; s < config.capacity; ++s) {
    if (gpu.table.counts[s] < 2) continue;  // one add: no order to compare
    const std::uint32_t e = emulated.placements[record_in_slot[s]];
    if (e >= config.capacity || emulated.table.counts[e] != gpu.table.counts[s]) {
      ++a.unmatched;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      const std::int64_t x = std::bit_cast<std::int32_t>(gpu.table.float_sums[s][c]);
      const std::int64_t y = std::bit_cast<std::int32_t>(emulated.table.float_sums[e][c]);
      ++a.compared;
      a.equal += x == y;
      a.worst_ulps = std::max(a.worst_ulps, std::abs(x - y));
    }
  }
  return a;
}

TEST(VulkanBackend, Float32BitsBesideTheEmulatorsSequentialOrder) {
  const RecordBatch batch = TracedBatch("cornell", 32, 4);
  FilterConfig config;
  config.capacity = 1u << 14;
  config.accumulation = Accumulation::kFloat32;
  const char* previous = std::getenv("LP_NUM_THREADS");
  const std::string saved = previous ? previous : "";
  for (const char* threads : {"", "1"}) {
    if (*threads) setenv("LP_NUM_THREADS", threads, 1);  // read when lavapipe creates its device
    std::string driver;
    const Float32Agreement a = CompareFloat32WithEmulator(batch, config, driver);
    std::printf(
        "%s%s float32 vs emulator (warp 8, round-robin): %llu of %llu multi-add slot sums bit-identical, worst %lld "
        "ulps; "
        "%llu slots held other records\n",
        driver.c_str(), *threads ? " with LP_NUM_THREADS=1" : "", (unsigned long long)a.equal,
        (unsigned long long)a.compared, (long long)a.worst_ulps, (unsigned long long)a.unmatched);
    EXPECT_GT(a.compared, 0u);
    // One lavapipe thread applies the atomics in the emulator's order: the emulator reproduces its bits.
    if (*threads && driver == "llvmpipe") {
      EXPECT_EQ(a.equal, a.compared);
    }
  }
  if (previous) {
    setenv("LP_NUM_THREADS", saved.c_str(), 1);
  } else {
    unsetenv("LP_NUM_THREADS");
  }
}

}  // namespace
}  // namespace hpsf::testing
