// Probe failures (a tiny table) and fingerprint aliases (8-bit fingerprints) happen, are counted, pass the
// table checker, and lose no light in the furnace.
#include "emulated/emulated_filter.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <set>

#include <gtest/gtest.h>

#include "reference/float_replay.h"
#include "reference/reference_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

int AliasedSlotCount(const EmulatedRun& run) {
  const std::vector<bool> aliased = AliasedSlots(run);
  return int(std::count(aliased.begin(), aliased.end(), true));
}

double MeanGreen(const Image& image) {
  double sum = 0.0;
  for (const glm::vec3& p : image.pixels) sum += p.y;
  return sum / double(image.pixels.size());
}

TEST(EmulatedFilter, FailuresAndAliasesAreCountedAndLoseNoLightInTheFurnace) {
  TraceOptions trace;
  trace.width = trace.height = 48;
  trace.samples_per_pixel = 8;
  trace.max_depth = -1;
  const RecordBatch batch = TraceRecords(LoadScene("furnace"), trace).batch;
  const double unfiltered = MeanGreen(UnfilteredImage(batch));

  FilterConfig tiny;
  tiny.capacity = 64;
  tiny.probe_limit = 4;
  FilterConfig aliasing;
  aliasing.capacity = 1024;
  aliasing.fingerprint_bits = 8;
  aliasing.normal_in_index = false;  // cells of different orientation share windows: more chances to alias
  const FilterConfig configs[] = {tiny, aliasing};
  for (int which = 0; which < 2; ++which) {
    const FilterConfig& config = configs[which];
    for (simt::Mode mode : {simt::Mode::kFast, simt::Mode::kFaithful}) {
      EmulatorOptions options;
      options.mode = mode;
      options.warp_size = 8;
      options.schedule = "random:4";
      const EmulatedRun run = EmulatedFilter(batch, config, options);
      if (which == 0) {
        EXPECT_GT(run.probe_failures, 100u);
      } else {
        EXPECT_GT(AliasedSlotCount(run), 0) << "8-bit fingerprints in shared windows must alias some cells";
      }
      // Filtering moves light between records of a cell; with the furnace's constant throughput it keeps the
      // total, wherever probe failures keep their own light and aliases average two cells.
      EXPECT_NEAR(MeanGreen(run.image), unfiltered, 1e-4 * unfiltered) << "capacity " << config.capacity;
    }
  }
}

TEST(EmulatedFilter, WithNothingFailedOrAliasedFixed64EqualsTheReferenceInBothModes) {
  TraceOptions trace;
  trace.width = trace.height = 32;
  trace.samples_per_pixel = 2;
  const RecordBatch batch = TraceRecords(LoadScene("cornell"), trace).batch;
  FilterConfig config;
  config.capacity = 1u << 16;
  const Image reference = ReferenceFilter(batch, config).image;
  for (simt::Mode mode : {simt::Mode::kFast, simt::Mode::kFaithful}) {
    for (std::uint32_t warp : {8u, 32u, 64u}) {
      EmulatorOptions options;
      options.mode = mode;
      options.warp_size = warp;
      options.schedule = "pct:9:3";
      const EmulatedRun run = EmulatedFilter(batch, config, options);
      ASSERT_EQ(run.probe_failures, 0u);
      for (std::size_t i = 0; i < reference.pixels.size(); ++i)
        ASSERT_EQ(run.image.pixels[i], reference.pixels[i]) << i;
    }
  }
}

}  // namespace
}  // namespace hpsf

namespace hpsf {
namespace {

// 64 records of one cell whose contributions span six orders of magnitude, so the order of float adds shows.
RecordBatch ContendedCell() {
  RecordBatch batch;
  batch.width = 64;
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 0.5;
  for (std::uint32_t i = 0; i < 64; ++i) {
    VertexSample v;
    v.pixel = i;
    v.position = glm::vec3(0.25f + 0.01f * float(i % 8), 0.5f, 0.5f);
    v.previous = v.position - glm::vec3(0.0f, 0.0f, 10.0f);
    const float scale = std::ldexp(1.0f, int(i % 20) - 10);
    v.contribution = glm::vec3(scale * (1.0f + 0.1f * float(i)), 0.3f * scale, 1.0f / float(i + 1));
    v.throughput = glm::vec3(0.5f);
    batch.records.push_back(MakeVertexRecord(v));
  }
  return batch;
}

FilterConfig OneCellConfig() {
  FilterConfig c;
  c.lod = false;
  c.cell_size = 1.0f;
  c.jitter_scale = 0.0f;
  c.normal = {NormalMode::kNone, 0};
  c.capacity = 64;
  c.accumulation = Accumulation::kFloat32;
  return c;
}

TEST(EmulatedFilter, Float32OrderReplaysToTheSameBitsAndDiffersBetweenSeeds) {
  const RecordBatch batch = ContendedCell();
  std::set<std::uint32_t> sums;
  for (std::uint32_t seed = 0; seed < 16; ++seed) {
    EmulatorOptions options;
    options.mode = simt::Mode::kFaithful;
    options.warp_size = 8;
    options.schedule = "random:" + std::to_string(seed);
    const EmulatedRun run = EmulatedFilter(batch, OneCellConfig(), options);
    ASSERT_EQ(run.float_add_order.size(), 64u * 3u);
    std::uint32_t used = 0;
    for (std::size_t entry = 0; entry < run.float_add_order.size(); ++entry) {
      const float table = run.table.float_sums[entry / 3][entry % 3];
      EXPECT_EQ(std::bit_cast<std::uint32_t>(ReplayFloatSum(batch.records, run.float_add_order[entry], int(entry % 3))),
                std::bit_cast<std::uint32_t>(table));
      if (run.float_add_order[entry].size() == 64) {
        used = std::uint32_t(entry / 3);
        EXPECT_EQ(run.table.counts[used], 64u);
      }
    }
    sums.insert(std::bit_cast<std::uint32_t>(run.table.float_sums[used][0]));
  }
  // The emulator reproduces a GPU's order dependence: seeds that order the adds differently give other bits.
  EXPECT_GT(sums.size(), 1u);
}

// Several filtered bounces' transport runs on the fast mode's workers (core/transport.h, RangeLoop): each record's
// lookup reads the table before the frame alone, so one worker and every core give the same transported light, reads
// and counts, and the same frame bit for bit. Under ThreadSanitizer (scripts/run-sanitizers.sh) the workers are plain
// threads it sees, so a lookup that wrote shared state would be a reported race.
TEST(EmulatedFilter, TheTransportGivesTheSameBitsOnOneWorkerAndOnEveryCore) {
  const Scene furnace = LoadScene("furnace");
  TraceOptions trace;
  trace.width = trace.height = 48;
  trace.samples_per_pixel = 4;
  trace.scattered = true;
  trace.filtered_vertices = 2;
  FilterConfig config;
  config.transport = true;
  config.frames = 2;
  config.capacity = 1u << 16;
  EmulatorOptions one;
  one.threads = 1;
  EmulatorOptions every;  // threads 0: every core
  const EmulatedRun first = EmulatedFilter(TraceRecords(furnace, trace).batch, config, one);
  trace.frame = config.frame = 1;
  const RecordBatch second = TraceRecords(furnace, trace).batch;
  const EmulatedRun on_one = EmulatedFilter(second, config, one, AccumulateKernel, &first.table);
  const EmulatedRun on_every = EmulatedFilter(second, config, every, AccumulateKernel, &first.table);
  ASSERT_GT(on_one.transport.found, 1000u);
  EXPECT_EQ(on_one.transport.found, on_every.transport.found);
  EXPECT_EQ(on_one.transport.missed, on_every.transport.missed);
  EXPECT_EQ(on_one.transport.scattered, on_every.transport.scattered);
  EXPECT_EQ(on_one.transport_read, on_every.transport_read);
  ASSERT_EQ(on_one.image.pixels.size(), on_every.image.pixels.size());
  EXPECT_EQ(0, std::memcmp(on_one.image.pixels.data(), on_every.image.pixels.data(),
                           on_one.image.pixels.size() * sizeof(glm::vec3)));
}

}  // namespace
}  // namespace hpsf
