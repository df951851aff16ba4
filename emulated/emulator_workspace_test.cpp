// A run in arrays kept from another run (emulated/emulator_workspace.h) is bit for bit the run in fresh memory:
// nothing of the earlier run's keys, table or image shows through, whichever run is the larger.
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "emulated/emulated_backend.h"
#include "emulated/emulated_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

RecordBatch Trace(const std::string& scene, std::uint32_t size, std::uint32_t spp, std::uint32_t frame = 0) {
  TraceOptions trace;
  trace.width = trace.height = size;
  trace.samples_per_pixel = spp;
  trace.frame = frame;
  return TraceRecords(LoadScene(scene), trace).batch;
}

template <typename T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void ExpectSameRun(const EmulatedRun& kept, const EmulatedRun& fresh, const std::string& what) {
  EXPECT_TRUE(SameBits(kept.image, fresh.image)) << what << ": image";
  EXPECT_TRUE(SameBytes(kept.keys, fresh.keys)) << what << ": keys";
  EXPECT_TRUE(SameBytes(kept.placements, fresh.placements)) << what << ": placements";
  EXPECT_TRUE(SameBytes(kept.table.tags, fresh.table.tags)) << what << ": tags";
  EXPECT_TRUE(SameBytes(kept.table.counts, fresh.table.counts)) << what << ": counts";
  EXPECT_TRUE(SameBytes(kept.table.fixed_sums, fresh.table.fixed_sums)) << what << ": fixed64 sums";
  EXPECT_TRUE(SameBytes(kept.table.float_sums, fresh.table.float_sums)) << what << ": float32 sums";
  EXPECT_EQ(kept.probe_failures, fresh.probe_failures) << what;
  EXPECT_EQ(kept.probe_lengths, fresh.probe_lengths) << what;
}

// Deterministic runs, so that the two runs may be compared bit for bit: fast mode on one worker, and faithful.
std::vector<EmulatorOptions> DeterministicOptions() {
  EmulatorOptions fast;
  fast.threads = 1;
  EmulatorOptions faithful;
  faithful.mode = simt::Mode::kFaithful;
  faithful.warp_size = 8;
  faithful.schedule = "random:3";
  return {fast, faithful};
}

TEST(EmulatorWorkspace, ARunInAnotherRunsArraysEqualsTheRunInFreshMemory) {
  const RecordBatch large = Trace("cornell", 40, 4);
  const RecordBatch small = Trace("furnace", 24, 2);
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    FilterConfig config;
    config.capacity = 4096;  // the same table for both: its slots hold the earlier run's cells unless cleared
    config.accumulation = accumulation;
    for (const EmulatorOptions& options : DeterministicOptions()) {
      for (const auto& [first, second] : {std::pair{&large, &small}, std::pair{&small, &large}}) {
        const std::string what = std::string(ToString(accumulation)) + ", " +
                                 (options.mode == simt::Mode::kFast ? "fast" : "faithful") + ", " +
                                 (first == &large ? "large then small" : "small then large");
        EmulatorWorkspace workspace;
        workspace.Recycle(EmulatedFilter(*first, config, options, AccumulateKernel, nullptr, {}, nullptr, &workspace));
        const void* kept_tags = workspace.tags.data();
        const void* kept_keys = workspace.keys.data();
        ASSERT_NE(kept_tags, nullptr) << what;
        const EmulatedRun kept =
            EmulatedFilter(*second, config, options, AccumulateKernel, nullptr, {}, nullptr, &workspace);
        // The oracle is fed: the table always, and the per-record arrays where the first run's were large enough.
        EXPECT_EQ(static_cast<const void*>(kept.table.tags.data()), kept_tags) << what;
        if (first == &large) {
          EXPECT_EQ(static_cast<const void*>(kept.keys.data()), kept_keys) << what;
        }
        ExpectSameRun(kept, EmulatedFilter(*second, config, options), what);
      }
    }
  }
}

// Reset recycles the backend's last run: each first frame here runs in the arrays of the one before.
TEST(EmulatorWorkspace, ABackendsFirstFramesEqualFramesInFreshMemory) {
  const RecordBatch frames[] = {Trace("cornell", 40, 4), Trace("furnace", 24, 2), Trace("cornell", 32, 2)};
  FilterConfig config;
  config.capacity = 8192;
  for (const EmulatorOptions& options : DeterministicOptions()) {
    EmulatedBackend backend(options);
    for (std::uint32_t k = 0; k < 3; ++k) {
      backend.Reset();  // each a first frame: the batches differ in shape
      config.frame = k;
      backend.FilterFrame(frames[k], config);
      ExpectSameRun(backend.run(), EmulatedFilter(frames[k], config, options), "frame " + std::to_string(k));
    }
  }
}

// In a sequence the backend recycles the run before the last: its third frame runs in its first frame's arrays.
TEST(EmulatorWorkspace, ASequencesFramesEqualTheSameFramesChainedInFreshMemory) {
  FilterConfig config;
  config.capacity = 8192;
  config.frames = 4;
  for (const EmulatorOptions& options : DeterministicOptions()) {
    EmulatedBackend backend(options);
    EmulatedRun previous;
    for (std::uint32_t k = 0; k < 4; ++k) {
      const RecordBatch batch = Trace("cornell", 32, 2, k);
      config.frame = k;
      backend.FilterFrame(batch, config);
      const FrameEffects effects = PlanFrameEffects(config, k);
      EmulatedRun fresh =
          EmulatedFilter(batch, config, options, AccumulateKernel, k == 0 ? nullptr : &previous.table, {}, &effects);
      ExpectSameRun(backend.run(), fresh, "frame " + std::to_string(k));
      previous = std::move(fresh);
    }
  }
}

}  // namespace
}  // namespace hpsf
