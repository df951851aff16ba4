// The statistical comparison of two renders (verifier/metrics/statistical_compare) on constructed images: its
// arithmetic against scipy's Welch test (p-values, degrees of freedom, the Sidak levels), no noise, NaN and the
// refusals. Renders: statistical_renders_test.cpp; the false-alarm rates: statistical_calibration_test.cpp.
#include "verifier/metrics/statistical_compare.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"

namespace hpsf::testing {
namespace {

// Two pixels in tiles of one pixel, so 6 tile tests, of images of 4 and 9 spp: each tile's nu is 3 and 8, the
// image mean's 6 and 16. Tile variances 0.5 and 0.2, the image mean's 0.1 and 0.05.
NoisyImage TwoPixels(glm::vec3 first, glm::vec3 second, float tile_variance, double mean_variance, std::uint32_t spp) {
  NoisyImage image{"constructed", Image(2, 1), Image(2, 1), Image(2, 1), 1, spp, glm::dvec3(mean_variance)};
  image.mean.pixels = {first, second};
  for (glm::vec3& v : image.variance.pixels) v = glm::vec3(tile_variance);
  for (glm::vec3& v : image.tile_variance.pixels) v = glm::vec3(tile_variance);
  return image;
}

// The expected figures are scipy's (scipy.stats.ttest_ind_from_stats(..., equal_var=False) for t and p, whose
// Welch-Satterthwaite dof is (va + vb)^2 / (va^2 / nu_a + vb^2 / nu_b)), and the Sidak levels
// 1 - (1 - 0.005)^(1/k) for k = 6 and 3. a has fewer spp, so its variances are floored by b's times 9/4: not a
// tile's (0.2 * 9/4 = 0.45 < 0.5), but the image mean's (0.05 * 9/4 = 0.1125 > 0.1, then on b's 16 dof).
TEST(StatisticalCompare, ConstructedImagesHaveScipysWelchTestAndSidakLevels) {
  const NoisyImage a = TwoPixels({3.0f, 2.0f, 0.5f}, {1.0f, 1.0f, 1.0f}, 0.5f, 0.1, 4);
  const NoisyImage b = TwoPixels({0.0f, 2.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 0.2f, 0.05, 9);
  const StatisticalComparison c = CompareStatistically(a, b);
  SCOPED_TRACE(c.ToString());
  EXPECT_NEAR(c.tile_level, 0.0008350747680885284, 1e-15);
  EXPECT_NEAR(c.mean_level, 0.0016694521863086509, 1e-15);
  EXPECT_EQ(c.tiles_tested, 2u);
  // Tile 0, red: t 3.586 on 5.547 dof, p 0.0132; as a z-test (p 3.4e-4) it would reject.
  EXPECT_EQ(c.worst.x, 0u);
  EXPECT_EQ(c.worst.channel, 0);
  EXPECT_NEAR(c.worst.t, 3.585685828003181, 1e-6);
  EXPECT_NEAR(c.worst.dof, 5.547169811320754, 1e-6);  // variances are floats: 0.2f is not 0.2
  EXPECT_NEAR(c.worst.p, 0.013217571130999708, 1e-8);
  EXPECT_EQ(c.tiles_rejected, 0u);
  // Image mean, red: 2 against 0.5 with a's variance floored to 0.1125 on 16 dof: t 3.721 on 27.88 dof, p 8.9e-4,
  // below its level. With a's own 0.1 on 6 dof it would be t 3.873 on 12.34 dof, p 0.0021.
  EXPECT_NEAR(c.mean[0].t, 3.7210420376762534, 1e-6);
  EXPECT_NEAR(c.mean[0].dof, 27.876288659793815, 1e-6);
  EXPECT_NEAR(c.mean[0].p, 0.0008876216873908789, 1e-9);
  EXPECT_EQ(c.mean[1].t, 0.0);
  EXPECT_FALSE(c.consistent);
  // a's image-mean variance 0.2, above the floor: t 3 on 9.16 dof, p 0.0147, which passes.
  NoisyImage noisier = a;
  noisier.mean_variance = glm::dvec3(0.2);
  const StatisticalComparison passes = CompareStatistically(noisier, b);
  EXPECT_NEAR(passes.mean[0].t, 3.0, 1e-9);
  EXPECT_NEAR(passes.mean[0].dof, 9.16030534351145, 1e-9);
  EXPECT_NEAR(passes.mean[0].p, 0.0146688981683718, 1e-9);
  EXPECT_TRUE(passes.consistent) << passes.ToString();
  // Red of pixel 0 at 6: the tile's p 5.26e-4 is below its level.
  const StatisticalComparison far =
      CompareStatistically(TwoPixels({6.0f, 2.0f, 0.5f}, {1.0f, 1.0f, 1.0f}, 0.5f, 0.2, 4), b);
  EXPECT_NEAR(far.worst.p, 0.0005257981003041197, 1e-9);
  EXPECT_EQ(far.tiles_rejected, 1u);
  EXPECT_FALSE(far.consistent);
}

// Equal spp: neither image is floored, whatever their variances (their difference is not skewed).
TEST(StatisticalCompare, ImagesOfEqualSppAreNotFloored) {
  const NoisyImage a = TwoPixels({3.0f, 2.0f, 0.5f}, {1.0f, 1.0f, 1.0f}, 0.5f, 0.1, 9);
  const NoisyImage b = TwoPixels({0.0f, 2.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 0.02f, 0.001, 9);
  const StatisticalComparison c = CompareStatistically(a, b);
  // Tile 0, red: t = 3 / sqrt(0.52), dof (0.52)^2 / (0.25 / 8 + 0.0004 / 8) = 8.64.
  EXPECT_NEAR(c.worst.t, 3.0 / std::sqrt(0.52), 1e-6);
  EXPECT_NEAR(c.worst.dof, 0.52 * 0.52 / (0.25 / 8.0 + 0.0004 / 8.0), 1e-4);
}

TEST(StatisticalCompare, WithoutNoiseAnyDifferenceRejectsAndEqualityPasses) {
  const NoisyImage a = TwoPixels(glm::vec3(1.0f), glm::vec3(1.0f), 0.0f, 0.0, 4);
  EXPECT_TRUE(CompareStatistically(a, a).consistent);
  NoisyImage b = a;
  b.mean.pixels[1].y = std::nextafter(1.0f, 2.0f);
  const StatisticalComparison c = CompareStatistically(a, b);
  EXPECT_FALSE(c.consistent);
  EXPECT_EQ(c.tiles_rejected, 1u);
  EXPECT_EQ(c.worst.x, 1u);
  EXPECT_EQ(c.worst.t, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(c.mean[1].t, -std::numeric_limits<double>::infinity());
}

TEST(StatisticalCompare, ANanRejectsAndIsTheWorst) {
  const NoisyImage a = TwoPixels(glm::vec3(1.0f), glm::vec3(1.0f), 1.0f, 1.0, 4);
  NoisyImage b = a;
  b.mean.pixels[1].x = std::numeric_limits<float>::quiet_NaN();
  b.mean.pixels[0].z = 1000.0f;
  const StatisticalComparison c = CompareStatistically(a, b);
  EXPECT_FALSE(c.consistent);
  EXPECT_EQ(c.tiles_rejected, 2u);
  EXPECT_EQ(c.worst.x, 1u);
  EXPECT_TRUE(std::isnan(c.worst.p));
}

TEST(StatisticalCompare, BadInputIsRefusedNamingTheImage) {
  const NoisyImage a = TwoPixels(glm::vec3(1.0f), glm::vec3(1.0f), 1.0f, 1.0, 4);
  NoisyImage wider = a;
  wider.source = "wider.exr";
  wider.mean = wider.variance = Image(3, 1);
  wider.tile_variance = Image(3, 1);
  EXPECT_THROW(CompareStatistically(a, wider), InputError);
  EXPECT_THROW(CompareStatistically(a, a, 0.0), InputError);
  NoisyImage coarser = a;
  coarser.tile_size = 2;
  coarser.tile_variance = Image(1, 1);
  EXPECT_THROW(CompareStatistically(a, coarser), InputError);
  NoisyImage sparse = a;
  sparse.source = "sparse.exr";
  sparse.samples_per_pixel = kMinimumStatisticalSpp - 1;
  try {
    CompareStatistically(a, sparse);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("sparse.exr: " + std::to_string(kMinimumStatisticalSpp - 1) + " samples per pixel"),
        std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("--spp " + std::to_string(kMinimumStatisticalSpp)), std::string::npos)
        << e.what();
  }
  // The calibration measures below the minimum on purpose.
  EXPECT_NO_THROW(CompareStatistically(a, sparse, 0.01, 1));
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
