// Are two renders the same image up to their noise? `hpsf diff --statistical` asks this of two EXRs written with
// --variance (verifier/metrics/pixel_variance.h), so that a regression test of a Monte Carlo renderer needs neither
// the same seed nor a hand-tuned tolerance.
//
// H0: both images estimate the same expected image. Two families of two-sided Welch t-tests (Welch 1947; for
// renders, Jung, Hanika and Dachsbacher, "Detecting Bias in Monte Carlo Renderers using Welch's t-test", JCGT
// 2020, who test block means for the reason below), each held at alpha / 2 by the Sidak correction, so the whole
// comparison wrongly rejects two consistent renders with probability at most alpha:
//  - per tile (8x8 pixels) and channel, t = (M_a - M_b) / sqrt(V_a + V_b), V the variance of the tile mean with
//    the correlation of pixels that share a cell, over 3 x tiles tests: power against a change of a region (a
//    broken cell, a wrong texture, a light leak). Not per pixel: a pixel's variance rests on its n samples, and at
//    a few spp it often misses most of the pixel's noise (every sample jittered into one cell, none into its
//    neighbour): two seeds of the Cornell box at 4 spp gave per-pixel |z| up to 49 against a threshold of 5.07.
//  - per channel, the image mean, over 3 tests: power against a small bias spread over the image (an albedo, a
//    light or a lost 1% of the energy), which no tile's test can see.
// Degrees of freedom by Welch-Satterthwaite, each image's nu = K (n - 1) for a mean over K pixels of n samples.
// Where the spp differ, the image of fewer samples takes at least the other's variance scaled to its samples (a
// render that missed the rare bright samples has a mean too low and a variance too small at once: without the floor
// 4 spp against 256 false-alarmed in 43% of pairs).
// The t-test takes each mean as normal; tile means of 64 n samples are close enough from kMinimumStatisticalSpp
// on, and below it the comparison refuses (measured false-alarm rates, docs/results.md, "Statistical comparison").
// Power against a shift delta of one channel's image mean: Phi(delta / sigma - t) + Phi(-delta / sigma - t)
// (MeanTestPower), t the mean threshold (3.14 at alpha 0.01), sigma = sqrt(V_a + V_b).
#ifndef HPSF_VERIFIER_METRICS_STATISTICAL_COMPARE_H
#define HPSF_VERIFIER_METRICS_STATISTICAL_COMPARE_H

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "verifier/metrics/channel_image.h"
#include "verifier/metrics/pixel_variance.h"

namespace hpsf {

// Below this many samples per pixel in either image, `diff --statistical` refuses: the measured false-alarm rate
// of two seeds exceeded alpha there.
constexpr std::uint32_t kMinimumStatisticalSpp = 4;

// An image with its noise: each pixel's variance (shown, not tested), each tile's and the image mean's.
struct NoisyImage {
  std::string source;  // the file, for messages
  Image mean;
  Image variance;
  Image tile_variance;  // one texel a tile: ceil(W / tile_size) x ceil(H / tile_size)
  std::uint32_t tile_size = 8;
  std::uint32_t samples_per_pixel = 0;
  glm::dvec3 mean_variance{0.0};
};

// A render's image with the variances EstimatePixelVariance gave it, as a file rendered with --variance holds them.
NoisyImage MakeNoisyImage(std::string source, const Image& mean, const PixelVariance& variance,
                          std::uint32_t samples_per_pixel);

// The mean (R, G, B), the variances (variance.*, tile_variance.*, found by name), the image mean's variance
// (metadata mean_variance), spp and variance_tile of an image rendered with --variance; InputError naming the file
// and what is missing or malformed otherwise.
NoisyImage ToNoisyImage(const ChannelImage& image);

struct TileT {
  std::uint32_t x = 0;  // the tile's top-left pixel
  std::uint32_t y = 0;
  int channel = 0;
  double t = 0.0;    // signed, a - b; infinite where both variances are 0 and the means differ, NaN for a NaN input
  double dof = 0.0;  // Welch-Satterthwaite
  double p = 1.0;    // two-sided
};

struct StatisticalComparison {
  double alpha = 0.01;
  std::uint32_t tile_size = 8;
  std::uint64_t tiles_tested = 0;
  std::uint64_t tiles_rejected = 0;  // tiles with at least one channel below the level
  TileT worst;                       // the smallest p (a NaN counts as the smallest)
  double tile_level = 0.0;           // a tile test rejects when p < this
  TileT mean[3];                     // the image mean's test per channel (x, y 0)
  double mean_level = 0.0;
  bool consistent = true;  // no test of either family rejected
  std::string ToString() const;
};

nlohmann::json ToJson(const StatisticalComparison& comparison);

// Throws InputError when the images' sizes or tiles differ, or either has fewer than minimum_spp (lower only to
// measure the rates below the minimum, tools/calibration).
StatisticalComparison CompareStatistically(const NoisyImage& a, const NoisyImage& b, double alpha = 0.01,
                                           std::uint32_t minimum_spp = kMinimumStatisticalSpp);

// The probability that the image-mean test of one channel rejects when the expected means differ by `bias`,
// sigma = sqrt(mean_variance_a + mean_variance_b), in the normal limit (many degrees of freedom); the family's
// power is at least this.
double MeanTestPower(double bias, double sigma, double alpha = 0.01);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_STATISTICAL_COMPARE_H
