// Are two renders the same image up to their noise? `hpsf diff --statistical` asks this of two EXRs written with
// --variance (tools/checks/pixel_variance.h), so that a regression test of a Monte Carlo renderer needs neither
// the same seed nor a hand-tuned tolerance.
//
// H0: both images estimate the same expected image, each pixel's error roughly normal with the variance given.
// Two families of two-sided z tests, each held at alpha / 2 by the Sidak correction, so the whole comparison
// wrongly rejects two consistent renders with probability at most alpha (under the normal approximation; Sidak's
// inequality holds for two-sided tests of correlated normal z, so pixels that share cells keep the level):
//  - per pixel and channel, z = (a - b) / sqrt(va + vb) over the 3P tests: power against a large change in few
//    pixels (a firefly, a broken cell, a wrong texel). A test with va + vb == 0 rejects exactly when a != b.
//  - per channel, the image mean, z = (mean_a - mean_b) / sqrt(mean_variance_a + mean_variance_b) over the 3
//    tests: power against a small bias spread over the image (an albedo, a light or a lost 1% of the energy),
//    which no single pixel's test can see. Its variance counts the correlation of pixels that share a cell.
// The alternative it rejects is a difference in the expected image: a pixel's shifted by about 5 of its standard
// deviations (the pixel threshold, 5.07 for 64x64), or a channel's mean shifted by delta, found with power
// Phi(delta / sigma - t) + Phi(-delta / sigma - t) (MeanTestPower), t the mean threshold (3.14 at alpha 0.01) and
// sigma = sqrt(mean_variance_a + mean_variance_b). Measured (property_tests/statistical_compare_test): the Cornell
// box looking at the floor, reference filter, 64x64 at 192 spp, green mean 0.0379 with 4.85e-5 a render: 1% more
// green is 5.5 sigma, power 0.992 (its z came out -6.37; two seeds gave |z| <= 0.85). In the plain view at 256 spp
// the light's edge pixels make it 3.4e-4 for a mean of 0.131: 1% is 2.7 sigma, power 0.34; there the light's own
// pixels (12 in green, little noise) show the 1% to the pixel test instead. Both tests take the errors as normal;
// a pixel of few heavy-tailed samples can pass its threshold more often than alpha says (two consistent renders
// above: worst |z| 3.57 of 5.07).
#ifndef HPSF_TOOLS_CHECKS_STATISTICAL_COMPARE_H
#define HPSF_TOOLS_CHECKS_STATISTICAL_COMPARE_H

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "tools/checks/channel_image.h"

namespace hpsf {

// An image with its noise: each pixel's variance and the variance of the image mean, per channel.
struct NoisyImage {
  Image mean;
  Image variance;
  glm::dvec3 mean_variance{0.0};
};

// The mean (R, G, B), the variance (variance.R, .G, .B, found by name) and the image mean's variance (metadata
// mean_variance, three numbers) of an image rendered with --variance; InputError naming the file and what is
// missing otherwise.
NoisyImage ToNoisyImage(const ChannelImage& image);

struct PixelZ {
  std::uint32_t x = 0;
  std::uint32_t y = 0;
  int channel = 0;
  double z = 0.0;  // signed, a - b; infinite where the variances are 0 and the values differ, NaN for a NaN input
};

struct StatisticalComparison {
  double alpha = 0.01;
  std::uint64_t pixels_tested = 0;
  std::uint64_t pixels_rejected = 0;  // pixels with at least one channel past the threshold
  PixelZ worst;                       // the largest |z| (a NaN counts as the largest)
  double pixel_threshold = 0.0;       // a pixel test rejects beyond |z| > this
  glm::dvec3 mean_z{0.0};
  double mean_threshold = 0.0;
  bool consistent = true;  // no test of either family rejected
  std::string ToString() const;
};

nlohmann::json ToJson(const StatisticalComparison& comparison);

// Throws InputError when the images' sizes differ.
StatisticalComparison CompareStatistically(const NoisyImage& a, const NoisyImage& b, double alpha = 0.01);

// The probability that the image-mean test of one channel rejects when the expected means differ by `bias`,
// sigma = sqrt(mean_variance_a + mean_variance_b); the family's power is at least this.
double MeanTestPower(double bias, double sigma, double alpha = 0.01);

}  // namespace hpsf

#endif  // HPSF_TOOLS_CHECKS_STATISTICAL_COMPARE_H
