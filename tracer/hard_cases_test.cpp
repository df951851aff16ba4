// The hard cases of docs/design/tracer.md: far from the origin, tiny, zero albedo channels, and
// unkeyable records on purpose.
#include <cmath>

#include <gtest/gtest.h>

#include "reference/reference_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

TraceOptions Options(std::uint32_t size, std::uint32_t spp) {
  TraceOptions o;
  o.width = o.height = size;
  o.samples_per_pixel = spp;
  return o;
}

bool AllFinite(const Image& image) {
  for (const glm::vec3& p : image.pixels) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  }
  return true;
}

glm::dvec3 Mean(const Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& p : image.pixels) sum += glm::dvec3(p);
  return sum / double(image.pixels.size());
}

TEST(HardCases, EveryBuiltinSceneIsFiniteFilteredAndUnfiltered) {
  for (const std::string& name : BuiltinSceneNames()) {
    const RecordBatch batch = TraceRecords(LoadScene(name), Options(32, 2)).batch;
    const FilterResult filtered = ReferenceFilter(batch, FilterConfig{});
    EXPECT_TRUE(AllFinite(filtered.image)) << name;
    EXPECT_TRUE(AllFinite(UnfilteredImage(batch))) << name;
    EXPECT_EQ(filtered.stats.rejected_non_finite + filtered.stats.rejected_negative, 0u) << name;
  }
}

// Moving the box by 1e5 changes float spacing from 2^-15 to 2^-7 mm: the image stays the same within noise.
TEST(HardCases, Far1e5EqualsTheUntranslatedBoxWithinNoise) {
  const Image near = UnfilteredImage(TraceRecords(LoadScene("cornell"), Options(32, 32)).batch);
  const Image far = UnfilteredImage(TraceRecords(LoadScene("cornell-far-1e5"), Options(32, 32)).batch);
  const glm::dvec3 a = Mean(near), b = Mean(far);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], a[c], 0.02 * a[c] + 1e-3) << "channel " << c;
}

// With every red albedo 0, the green and blue light transport is untouched: the unfiltered green and blue
// channels equal the Cornell box's bit for bit, and red survives only where the camera sees the light itself.
// A division by albedo anywhere would have produced NaN or Inf here.
TEST(HardCases, ZeroRedKeepsGreenAndBlueAndNeverDividesByAlbedo) {
  const RecordBatch cornell = TraceRecords(LoadScene("cornell"), Options(32, 4)).batch;
  const RecordBatch zero_red = TraceRecords(LoadScene("cornell-zero-red"), Options(32, 4)).batch;
  const Image a = UnfilteredImage(cornell), b = UnfilteredImage(zero_red);
  ASSERT_TRUE(AllFinite(b));
  ASSERT_TRUE(AllFinite(ReferenceFilter(zero_red, FilterConfig{}).image));
  int red_pixels = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    EXPECT_EQ(a.pixels[i].y, b.pixels[i].y);
    EXPECT_EQ(a.pixels[i].z, b.pixels[i].z);
    red_pixels += b.pixels[i].x > 0.0f;
  }
  for (const Record& r : zero_red.records) {
    if (shared::RecordHasVertex(r)) {
      EXPECT_EQ(r.throughput.x, 0.0f);
    }
  }
  EXPECT_LT(red_pixels, int(a.pixels.size()) / 20) << "red must come only from the light seen directly";
}

TEST(HardCases, TinyFixedCellsMakeUnkeyableRecordsThatFallBack) {
  const RecordBatch batch = TraceRecords(LoadScene("cornell"), Options(24, 2)).batch;
  FilterConfig config;
  config.lod = false;
  config.cell_size = 1e-30f;
  const FilterResult result = ReferenceFilter(batch, config);
  EXPECT_EQ(result.stats.unkeyable, result.stats.records_with_vertex);
  EXPECT_EQ(result.stats.cells, 0u);
  // Every record fell back to its own contribution: the filtered image is the unfiltered one.
  const Image unfiltered = UnfilteredImage(batch);
  for (std::size_t i = 0; i < unfiltered.pixels.size(); ++i) EXPECT_EQ(result.image.pixels[i], unfiltered.pixels[i]);
}

}  // namespace
}  // namespace hpsf
