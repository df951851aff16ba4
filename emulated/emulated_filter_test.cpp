// Probe failures (a tiny table) and fingerprint aliases (8-bit fingerprints) happen, are counted, pass the
// table checker, and lose no light in the furnace.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "emulated/emulated_filter.h"
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
      for (std::size_t i = 0; i < reference.pixels.size(); ++i) ASSERT_EQ(run.image.pixels[i], reference.pixels[i]) << i;
    }
  }
}

}  // namespace
}  // namespace hpsf
