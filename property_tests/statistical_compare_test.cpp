// The statistical comparison of two renders (tools/checks/statistical_compare): two seeds of the Cornell box are
// consistent with noise, 1% more green is seen by the image-mean test, one pixel ten times brighter by the pixel
// test; constructed images check the arithmetic (z, the Sidak thresholds, no noise, NaN). The renders use fixed
// seeds, so each verdict is one fixed outcome; the power stated for the 1% bias is computed from the renders.
#include <cmath>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"
#include "reference/reference_filter.h"
#include "tools/checks/pixel_variance.h"
#include "tools/checks/statistical_compare.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf::testing {
namespace {

// 64x64 at 192 spp: 786,432 records a render, enough for the image-mean test to find a 1% bias of green with power
// 0.99 (below); the two renders take 6 s in a Debug build on two idle cores (14 s under load), 2 s optimised.
constexpr std::uint32_t kSize = 64;
constexpr std::uint32_t kSpp = 192;

// The Cornell box looking down at the floor, the light out of view: the light's edge pixels, whose noise no filter
// touches, would otherwise hold most of the image mean's variance (pixel_variance_test measures it) and take the
// mean test's power against a 1% bias from 0.99 to below a third at this cost (0.34 measured at 256 spp).
NoisyImage Render(std::uint32_t seed) {
  Scene scene = LoadScene("cornell");
  scene.camera.look_at = glm::dvec3(278.0, 0.0, 280.0);
  TraceOptions trace;
  trace.width = trace.height = kSize;
  trace.samples_per_pixel = kSpp;
  trace.seed = seed;
  const RecordBatch batch = TraceRecords(scene, trace).batch;
  FilterConfig config;
  config.seed = seed;
  const FilterResult result = ReferenceFilter(batch, config);
  const PixelVariance v = EstimatePixelVariance(batch, result.placement, result.cells.size());
  return {result.image, v.variance, v.mean_variance};
}

glm::dvec3 Mean(const Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& v : image.pixels) sum += glm::dvec3(v);
  return sum / double(image.pixels.size());
}

// One test, so that the two renders are made once (ctest runs every test in its own process).
TEST(StatisticalCompare, TwoSeedsAreConsistentButOnePercentMoreGreenOrOneBrightPixelIsNot) {
  const NoisyImage a = Render(11), b = Render(12);
  {
    SCOPED_TRACE("two seeds");
    const StatisticalComparison c = CompareStatistically(a, b);
    std::printf("two seeds: %s\n", c.ToString().c_str());
    EXPECT_TRUE(c.consistent) << c.ToString();
    EXPECT_EQ(c.pixels_tested, kSize * kSize);
    EXPECT_EQ(c.pixels_rejected, 0u);
  }
  {
    // Green scaled by 1.01 as a render with 1% more green would be: its mean, and its variances by 1.01^2. No
    // single pixel's test sees 1% (each pixel's noise is several percent); the image mean's does.
    SCOPED_TRACE("1% more green");
    NoisyImage greener = b;
    for (glm::vec3& v : greener.mean.pixels) v.y *= 1.01f;
    for (glm::vec3& v : greener.variance.pixels) v.y *= 1.01f * 1.01f;
    greener.mean_variance.y *= 1.01 * 1.01;
    const double power = MeanTestPower(0.01 * Mean(b.mean).y, std::sqrt(a.mean_variance.y + b.mean_variance.y));
    const StatisticalComparison c = CompareStatistically(a, greener);
    std::printf("green mean %.5f, its sigma %.3g per render, power against 1%%: %.4f\n1%% more green: %s\n",
                Mean(b.mean).y, std::sqrt(b.mean_variance.y), power, c.ToString().c_str());
    EXPECT_GE(power, 0.99);
    EXPECT_FALSE(c.consistent) << c.ToString();
    EXPECT_GT(std::abs(c.mean_z.y), c.mean_threshold) << c.ToString();
    EXPECT_LE(std::abs(c.mean_z.x), c.mean_threshold) << c.ToString();
    EXPECT_EQ(c.pixels_rejected, 0u) << "1% is within every pixel's noise: " << c.ToString();
  }
  {
    // A typical pixel (its green nearest the image's mean green) ten times brighter: the image mean moves by
    // 0.2%, within its noise, but that pixel's test sees it.
    SCOPED_TRACE("one pixel ten times brighter");
    NoisyImage changed = b;
    const double green = Mean(changed.mean).y;
    std::size_t typical = 0;
    for (std::size_t p = 0; p < changed.mean.pixels.size(); ++p) {
      if (std::abs(changed.mean.pixels[p].y - green) < std::abs(changed.mean.pixels[typical].y - green)) typical = p;
    }
    changed.mean.pixels[typical] *= 10.0f;
    const StatisticalComparison c = CompareStatistically(a, changed);
    std::printf("pixel %zu ten times brighter: %s\n", typical, c.ToString().c_str());
    EXPECT_FALSE(c.consistent);
    EXPECT_EQ(c.pixels_rejected, 1u) << c.ToString();
    EXPECT_EQ(c.worst.x, typical % kSize);
    EXPECT_EQ(c.worst.y, typical / kSize);
    EXPECT_LE(std::abs(c.mean_z.y), c.mean_threshold) << c.ToString();
  }
}

NoisyImage Constant(std::uint32_t width, glm::vec3 value, glm::vec3 variance, glm::dvec3 mean_variance) {
  NoisyImage image{Image(width, 1), Image(width, 1), mean_variance};
  for (glm::vec3& v : image.mean.pixels) v = value;
  for (glm::vec3& v : image.variance.pixels) v = variance;
  return image;
}

// Two pixels, so 6 pixel tests: Sidak at alpha / 2 = 0.005 puts the pixel threshold at 3.3409 and the 3 mean tests'
// at 3.1435 (from the normal quantile, computed apart). z = 3.2 in blue, in both pixels and in the mean, lies
// between them: only the mean test rejects. Without the correction the thresholds would be 2.81 and rejects both.
TEST(StatisticalCompare, ConstructedImagesHaveTheirZAndSidakThresholds) {
  const NoisyImage a = Constant(2, glm::vec3(1.0f, 2.0f, 3.2f), glm::vec3(0.5f), glm::dvec3(0.5));
  const NoisyImage b = Constant(2, glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(0.5f), glm::dvec3(0.5));
  const StatisticalComparison c = CompareStatistically(a, b);
  EXPECT_NEAR(c.pixel_threshold, 3.3408993937712923, 1e-9);
  EXPECT_NEAR(c.mean_threshold, 3.1434915798794467, 1e-9);
  EXPECT_EQ(c.pixels_tested, 2u);
  EXPECT_EQ(c.pixels_rejected, 0u);
  EXPECT_NEAR(c.worst.z, 3.2, 1e-6);
  EXPECT_EQ(c.worst.channel, 2);
  EXPECT_NEAR(c.mean_z.x, 1.0, 1e-12);
  EXPECT_EQ(c.mean_z.y, 0.0);
  EXPECT_NEAR(c.mean_z.z, 3.2, 1e-6);
  EXPECT_FALSE(c.consistent);
  // The same a little below the mean's threshold passes everything.
  const NoisyImage closer = Constant(2, glm::vec3(1.0f, 2.0f, 3.1f), glm::vec3(0.5f), glm::dvec3(0.5));
  EXPECT_TRUE(CompareStatistically(closer, b).consistent);
}

TEST(StatisticalCompare, WithoutNoiseAnyDifferenceRejectsAndEqualityPasses) {
  const NoisyImage a = Constant(3, glm::vec3(1.0f), glm::vec3(0.0f), glm::dvec3(0.0));
  EXPECT_TRUE(CompareStatistically(a, a).consistent);
  NoisyImage b = a;
  b.mean.pixels[1].y = std::nextafter(1.0f, 2.0f);
  const StatisticalComparison c = CompareStatistically(a, b);
  EXPECT_FALSE(c.consistent);
  EXPECT_EQ(c.pixels_rejected, 1u);
  EXPECT_EQ(c.worst.x, 1u);
  EXPECT_EQ(c.worst.z, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(c.mean_z.y, -std::numeric_limits<double>::infinity());
}

TEST(StatisticalCompare, ANanRejectsAndIsTheWorst) {
  const NoisyImage a = Constant(3, glm::vec3(1.0f), glm::vec3(1.0f), glm::dvec3(1.0));
  NoisyImage b = a;
  b.mean.pixels[2].x = std::numeric_limits<float>::quiet_NaN();
  b.mean.pixels[0].z = 1000.0f;
  const StatisticalComparison c = CompareStatistically(a, b);
  EXPECT_FALSE(c.consistent);
  EXPECT_EQ(c.pixels_rejected, 2u);
  EXPECT_EQ(c.worst.x, 2u);
  EXPECT_TRUE(std::isnan(c.worst.z));
}

TEST(StatisticalCompare, ImagesOfDifferentSizesAreBadInput) {
  const NoisyImage a = Constant(3, glm::vec3(1.0f), glm::vec3(1.0f), glm::dvec3(1.0));
  const NoisyImage b = Constant(2, glm::vec3(1.0f), glm::vec3(1.0f), glm::dvec3(1.0));
  EXPECT_THROW(CompareStatistically(a, b), InputError);
  EXPECT_THROW(CompareStatistically(a, a, 0.0), InputError);
}

// The power of the mean test: at a shift of sigma times the threshold it rejects half the time, at no shift with
// the per-test level 1 - (1 - 0.005)^(1/3).
TEST(StatisticalCompare, MeanTestPowerHasItsKnownPoints) {
  EXPECT_NEAR(MeanTestPower(3.1434915798794467, 1.0), 0.5, 1e-6);
  EXPECT_NEAR(MeanTestPower(0.0, 1.0), 1.0 - std::pow(0.995, 1.0 / 3.0), 1e-9);
  EXPECT_NEAR(MeanTestPower(-3.1434915798794467 * 2.0, 2.0), 0.5, 1e-6);
}

}  // namespace
}  // namespace hpsf::testing
