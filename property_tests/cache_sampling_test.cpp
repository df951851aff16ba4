// Caching along subpaths (tracer/cache_sampling.h, Roth et al. §3.2 eq. 1) in the furnace, where every surface has
// albedo a = 0.5 and emits e = 1: a stored vertex's light, the light of the next l_len vertices without its own albedo,
// has the exact expectation e (1 - a^l_len) / (1 - a). The mean over every sample meets it for each l_len, and so does
// every HashCache cell's average once the samples are cached; a path that counts one vertex too many or too few misses
// it by a^l_len, far outside the test's bound. The samples do not depend on the thread count.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "core/fixed_point_scale.h"
#include "core/hashcache_update.h"
#include "core/shared/hashcache_cell.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf::testing {
namespace {

struct Moments {
  double mean = 0.0, standard_error = 0.0;
};

Moments MomentsOf(const std::vector<double>& values) {
  double sum = 0.0, squares = 0.0;
  for (const double v : values) sum += v, squares += v * v;
  const double n = double(values.size()), mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, squares / n - mean * mean) / n)};
}

TraceOptions FurnaceTrace(std::uint32_t size, std::uint32_t spp, int threads) {
  TraceOptions trace;
  trace.width = trace.height = size;
  trace.samples_per_pixel = spp;
  trace.seed = 3;
  trace.threads = threads;
  return trace;
}

// For l_len 1 to 4 at l_store 3, 32 x 32 pixels and 4 spp (12,288 samples each): every path reaches all its vertices
// (the furnace is closed), and the mean light per channel lies within 5 standard errors of the exact expectation
// (a false alarm once in 1.7 million runs of a normal mean; the standard error is below 0.004 where a vertex too many
// or too few moves the mean by at least 0.0625).
TEST(CacheSampling, TheFurnacesLightIsTheGeometricSeriesOfItsLength) {
  const PreparedScene furnace(LoadScene("furnace"), 0);
  for (std::uint32_t length = 1; length <= 4; ++length) {
    const CacheSampling sampling{3, length};
    const CacheTraceResult traced = TraceCacheSamples(furnace, FurnaceTrace(32, 4, 0), sampling);
    ASSERT_EQ(traced.samples.size(), 32u * 32u * 4u * 3u);
    const double exact = (1.0 - std::pow(0.5, double(length))) / (1.0 - 0.5);
    for (int c = 0; c < 3; ++c) {
      std::vector<double> values;
      for (const HashCacheSample& s : traced.samples) values.push_back(s.light[c]);
      const Moments m = MomentsOf(values);
      if (c == 0) {
        std::printf("l_len %u: mean %.7f +- %.5f, exact %.5f (%.2f standard errors)\n", length, m.mean,
                    m.standard_error, exact, (m.mean - exact) / m.standard_error);
      }
      EXPECT_LT(m.standard_error, 0.004);
      EXPECT_LT(std::abs(m.mean - exact), 5.0 * m.standard_error) << "l_len " << length << ", channel " << c;
    }
  }
}

// The samples of one and of two tracing threads, bit for bit.
TEST(CacheSampling, TheSamplesDoNotDependOnTheThreadCount) {
  const PreparedScene cornell(LoadScene("cornell"), 0);
  const CacheTraceResult one = TraceCacheSamples(cornell, FurnaceTrace(24, 2, 1), {3, 3});
  const CacheTraceResult two = TraceCacheSamples(cornell, FurnaceTrace(24, 2, 2), {3, 3});
  ASSERT_EQ(one.samples.size(), two.samples.size());
  for (std::size_t i = 0; i < one.samples.size(); ++i) {
    ASSERT_EQ(std::memcmp(&one.samples[i], &two.samples[i], sizeof(HashCacheSample)), 0) << i;
  }
}

// The furnace's samples at l_len 3 cached (fixed64, 2^5 finest cells per axis): every finest cell with at least 64
// samples on its front averages the exact 1.75 within 5 of its own standard errors (the samples' spread over the
// square root of its count).
TEST(CacheSampling, EveryCachedCellAveragesTheFurnacesLight) {
  const Scene scene = LoadScene("furnace");
  const PreparedScene furnace(scene, 0);
  const CacheTraceResult traced = TraceCacheSamples(furnace, FurnaceTrace(48, 8, 0), {3, 3});
  std::vector<OccupancyTriangle> triangles;
  for (const Triangle& t : scene.triangles) triangles.push_back({t.p0, t.p1, t.p2});
  const shared::OccupancyGrid grid = GridOver(triangles, 5, "furnace");
  std::vector<CuckooMap> maps;
  for (const OccupancyLevel& level : OccupancyPyramid(grid, triangles)) {
    maps.push_back(BuildCuckooMap(OccupiedKeys(level), {.level = std::uint32_t(level.level())}).map);
  }
  std::vector<glm::vec3> lights;
  std::vector<double> values;
  for (const HashCacheSample& s : traced.samples) lights.push_back(s.light), values.push_back(s.light.x);
  const int bits = ChooseFixedPointBitsOf(lights);
  HashCache cache = EmptyHashCache(grid, std::move(maps), Accumulation::kFixed64, bits);
  const HashCacheUpdateReport report = UpdateHashCache(cache, traced.samples);
  const double spread = MomentsOf(values).standard_error * std::sqrt(double(values.size()));
  std::uint32_t judged = 0, worst_cell = 0;
  double worst = 0.0;
  const HashCacheData& finest = cache.levels[0].data;
  for (std::size_t slot = 0; slot < finest.front.size(); ++slot) {
    const std::uint64_t n = finest.counts[2 * slot];
    if (n < 64) continue;
    ++judged;
    const double average = IntegerSumValue(finest.fixed_sums[6 * slot], Accumulation::kFixed64, bits) / double(n);
    const double z = std::abs(average - 1.75) / (spread / std::sqrt(double(n)));
    if (z > worst) worst = z, worst_cell = cache.levels[0].map.slots[slot];
  }
  std::printf(
      "%zu samples, %llu missed; %u finest cells with 64 or more on their front, the worst %.2f standard "
      "errors off (cell %u)\n",
      traced.samples.size(), (unsigned long long)report.missed, judged, worst, worst_cell);
  EXPECT_GT(judged, 100u);
  EXPECT_LT(worst, 5.0);
}

}  // namespace
}  // namespace hpsf::testing
