// The bias and variance split (verifier/metrics/error_split.h): MSE = bias^2 + variance + the reference's variance for
// any images; an estimator that adds a known bias b to unbiased noise of known variance s2 comes out at b^2 and s2
// (200 seeds of 64x64 pixels from the counter RNG; tolerances of five standard errors, which a fixed seed never
// crosses, and which a bias of twice b or a variance of twice s2 would cross by far); and the reference's noise is
// taken out of the bias.
#include "verifier/metrics/error_split.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/shared/rng.h"

namespace hpsf {
namespace {

// Uniform on [-a, a): variance a^2 / 3.
double Noise(std::uint32_t seed, std::uint32_t pixel, std::uint32_t channel, double a) {
  return a * (2.0 * double(shared::RandomFloat({seed, 0, pixel, 0, 0}, channel)) - 1.0);
}

std::vector<Image> Estimates(int seeds, double bias, double a, const Image& truth) {
  std::vector<Image> images;
  for (int s = 0; s < seeds; ++s) {
    Image image = truth;
    for (std::size_t p = 0; p < image.pixels.size(); ++p) {
      for (int c = 0; c < 3; ++c) image.pixels[p][c] += float(bias + Noise(std::uint32_t(s), std::uint32_t(p), c, a));
    }
    images.push_back(image);
  }
  return images;
}

Image Truth() {
  Image truth(64, 64);
  for (std::size_t p = 0; p < truth.pixels.size(); ++p) truth.pixels[p] = glm::vec3(float(p % 7), 1.0f, 0.25f);
  return truth;
}

TEST(ErrorSplit, TheTermsSumToTheMse) {
  const Image truth = Truth();
  const std::vector<Image> images = Estimates(3, 0.3, 0.5, truth);
  Image noise(64, 64);
  for (glm::vec3& p : noise.pixels) p = glm::vec3(0.01f);
  const ErrorSplit split = SplitError(images, truth, &noise);
  EXPECT_NEAR(split.mse, split.bias2 + split.variance + split.reference_variance, 1e-12 * split.mse);
  EXPECT_NEAR(split.relmse, split.rel_bias2 + split.rel_variance + split.rel_reference_variance, 1e-12 * split.relmse);
  EXPECT_EQ(split.values, 64u * 64u * 3u);
}

TEST(ErrorSplit, AKnownBiasAndVarianceComeOut) {
  const Image truth = Truth();
  const double bias = 0.05, a = 0.5, s2 = a * a / 3.0;
  const ErrorSplit split = SplitError(Estimates(200, bias, a, truth), truth, nullptr);
  // Standard errors over 12,288 values and 200 seeds: the variance's about s2 sqrt(0.8 / 12288 / 199) (uniform
  // noise's kurtosis 1.8), the bias^2's about 2 b sqrt(s2 / 200 / 12288).
  EXPECT_NEAR(split.variance, s2, 5.0 * s2 * std::sqrt(0.8 / 12288.0 / 199.0));
  EXPECT_NEAR(split.bias2, bias * bias, 5.0 * 2.0 * bias * std::sqrt(s2 / 200.0 / 12288.0));
  // The relative split weighs each value by 1 / (r^2 + 0.01): a uniform bias and noise come out at b^2 and s2
  // times the mean weight, within the same five standard errors scaled by the largest weight.
  double weights = 0.0, largest = 0.0;
  for (const glm::vec3& r : truth.pixels) {
    for (int c = 0; c < 3; ++c) {
      weights += 1.0 / (double(r[c]) * r[c] + 0.01);
      largest = std::max(largest, 1.0 / (double(r[c]) * r[c] + 0.01));
    }
  }
  const double mean_weight = weights / double(truth.pixels.size() * 3);
  EXPECT_NEAR(split.rel_variance, s2 * mean_weight, 5.0 * s2 * std::sqrt(0.8 / 12288.0 / 199.0) * largest);
  EXPECT_NEAR(split.rel_bias2, bias * bias * mean_weight, 5.0 * 2.0 * bias * std::sqrt(s2 / 200.0 / 12288.0) * largest);
  const ErrorSplit unbiased = SplitError(Estimates(200, 0.0, a, truth), truth, nullptr);
  EXPECT_NEAR(unbiased.bias2, 0.0, 5.0 * s2 / 200.0 / std::sqrt(12288.0));
  // The stated standard error is the one expected: Var((m - r)^2 - s2 / K) = 2 (s2 / K)^2 for nearly normal m
  // (200 uniform draws), over 12,288 values.
  const double expected = std::sqrt(2.0) * s2 / 200.0 / std::sqrt(12288.0);
  EXPECT_NEAR(unbiased.bias2_standard_error, expected, 0.1 * expected);
}

// The image mean's bias: a known bias b comes out within five of its stated standard errors, and no bias within five
// of zero; the standard error is what 200 seeds of 12,288 uniform values give, s2 / sqrt(200 x 12288) (rejecting a
// bias of b = 0.05 by more than 700 of them).
TEST(ErrorSplit, TheImageMeanBiasAndItsStandardError) {
  const Image truth = Truth();
  const double a = 0.5, s2 = a * a / 3.0;
  const double expected = std::sqrt(s2 / (200.0 * 12288.0));
  const ErrorSplit biased = SplitError(Estimates(200, 0.05, a, truth), truth, nullptr);
  EXPECT_NEAR(biased.mean_error_standard_error, expected, 0.2 * expected);
  EXPECT_NEAR(biased.mean_error, 0.05, 5.0 * biased.mean_error_standard_error);
  const ErrorSplit unbiased = SplitError(Estimates(200, 0.0, a, truth), truth, nullptr);
  EXPECT_LT(std::abs(unbiased.mean_error), 5.0 * unbiased.mean_error_standard_error);
}

TEST(ErrorSplit, TheReferenceNoiseLeavesTheBias) {
  const Image truth = Truth();
  const std::vector<Image> images = Estimates(4, 0.2, 0.1, truth);
  Image noise(64, 64);
  for (glm::vec3& p : noise.pixels) p = glm::vec3(0.001f);
  EXPECT_NEAR(SplitError(images, truth, nullptr).bias2 - SplitError(images, truth, &noise).bias2, 0.001, 1e-9);
}

}  // namespace
}  // namespace hpsf
