// The variance-aware adaptive temporal blend (--temporal adaptive-variance, core/shared/temporal_blend.h), label
// `adaptive`. Cells built from known distributions, blended by the shared BlendCell as every backend blends them:
// - a steady cell (history and frame from one normal distribution) is taken for changed only when the frame's mean
//   brightness lies more than two standard deviations of the predicted noise from the history's: a false alarm of
//   P(|Z| > 2) = 4.6% under the normal model, a little more with the variance estimated from the cell's own samples.
//   The test holds the measured rate over 20,000 cells (binomial standard deviation 0.15%) to [3%, 7%]; plain
//   adaptive takes every one of them for changed (its change is |f - h| / (f + h), positive whenever f != h);
// - a cell whose light moved by 5 standard deviations of the frame's noise is taken for changed in at least 99% of
//   20,000 (the normal model's power is 99.9%), and forgets at least 70% of what plain adaptive forgets;
// - where the noise explains none of the difference (a cell without variance), adaptive-variance is adaptive, bit for
//   bit; without a change it is integration, bit for bit.

#include <cmath>
#include <cstdint>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/accumulation.h"
#include "core/error.h"
#include "core/filter_config.h"
#include "core/shared/rng.h"
#include "core/shared/temporal_blend.h"
#include "core/temporal.h"

namespace hpsf::testing {
namespace {

// A standard normal from the counter RNG (Box-Muller).
double Normal(std::uint32_t cell, std::uint32_t sample) {
  const std::uint32_t prefix = shared::RngPrefix(shared::RngCounter{11, 0, cell, sample, 0});
  const double u1 = 1.0 - double(shared::RandomFloatFromPrefix(prefix, 0));  // in (0, 1]
  const double u2 = shared::RandomFloatFromPrefix(prefix, 1);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}

struct Cell {
  glm::dvec3 old_sum{0.0}, frame_sum{0.0};
  double old_square = 0.0, frame_square = 0.0;
  std::uint64_t old_count = 0, frame_count = 0;
};

constexpr std::uint32_t kHistory = 64, kCells = 20000;
constexpr double kMean = 1.0, kSigma = 0.3;  // of each grey sample's channel

// A grey cell of kHistory samples and a frame of one, the frame's shifted by `shift` channel deviations.
Cell GreyCell(std::uint32_t index, double shift) {
  Cell c;
  for (std::uint32_t s = 0; s <= kHistory; ++s) {
    const bool frame = s == kHistory;
    const double x = kMean + kSigma * (Normal(index, s) + (frame ? shift : 0.0));
    const double y = 3.0 * x;
    (frame ? c.frame_sum : c.old_sum) += glm::dvec3(x);
    (frame ? c.frame_square : c.old_square) += y * y;
    ++(frame ? c.frame_count : c.old_count);
  }
  return c;
}

shared::TemporalBlend Blend(const char* mode, const Cell& c) {
  const shared::TemporalParams p = MakeTemporalParams(ParseTemporal(mode), Accumulation::kFloat32, 0, 0);
  return shared::BlendCell(p, c.old_sum, c.old_count, c.frame_sum, c.frame_count, c.old_square, c.frame_square);
}

struct Rates {
  double changed = 0.0;      // the fraction of cells whose history weight fell below integration's
  double mean_weight = 0.0;  // the history's weight over integration's, averaged
};

Rates Measure(const char* mode, double shift) {
  Rates r;
  for (std::uint32_t i = 0; i < kCells; ++i) {
    const shared::TemporalBlend b = Blend(mode, GreyCell(i, shift));
    const double integration = double(kHistory) / double(kHistory + 1);
    r.changed += b.alpha < integration ? 1.0 / kCells : 0.0;
    r.mean_weight += b.alpha / integration / kCells;
  }
  return r;
}

TEST(TemporalVariance, ASteadyCellIsTakenForChangedOnlyAtTheFalseAlarmRate) {
  const Rates variance = Measure("adaptive-variance", 0.0);
  const Rates plain = Measure("adaptive", 0.0);
  std::printf(
      "steady: adaptive-variance takes %.4f for changed (history weight %.4f of integration's), adaptive "
      "%.4f (%.4f)\n",
      variance.changed, variance.mean_weight, plain.changed, plain.mean_weight);
  EXPECT_GT(variance.changed, 0.03);
  EXPECT_LT(variance.changed, 0.07);
  EXPECT_GT(plain.changed, 0.999);
  EXPECT_GT(variance.mean_weight, 0.99);
  EXPECT_LT(plain.mean_weight, 0.95);
}

TEST(TemporalVariance, ALightThatMovedFiveDeviationsIsTakenForChanged) {
  const Rates variance = Measure("adaptive-variance", 5.0);
  const Rates plain = Measure("adaptive", 5.0);
  std::printf(
      "moved by 5 deviations: adaptive-variance takes %.4f for changed (history weight %.4f), adaptive "
      "%.4f (%.4f)\n",
      variance.changed, variance.mean_weight, plain.changed, plain.mean_weight);
  EXPECT_GT(variance.changed, 0.99);
  // The change is adaptive's scaled by 1 - 4 noise / d^2, about 1 - 4 / 25 at 5 deviations: it forgets at least 70% of
  // what adaptive forgets.
  EXPECT_GT(1.0 - variance.mean_weight, 0.7 * (1.0 - plain.mean_weight));
}

TEST(TemporalVariance, WithoutNoiseItIsAdaptiveAndWithoutChangeIntegration) {
  Cell exact;  // every sample the same: no variance, so any difference is change
  exact.old_sum = glm::dvec3(64.0);
  exact.old_count = 64;
  exact.old_square = 64.0 * 9.0;
  exact.frame_sum = glm::dvec3(2.0);
  exact.frame_count = 1;
  exact.frame_square = 36.0;
  const shared::TemporalBlend v = Blend("adaptive-variance", exact), a = Blend("adaptive", exact);
  EXPECT_EQ(v.alpha, a.alpha);
  EXPECT_EQ(v.sum, a.sum);
  EXPECT_EQ(v.count, a.count);
  Cell same = exact;  // the frame equal to the history
  same.frame_sum = glm::dvec3(1.0);
  same.frame_square = 9.0;
  const shared::TemporalBlend s = Blend("adaptive-variance", same);
  EXPECT_TRUE(s.integrated);

  EXPECT_EQ(ParseTemporal("adaptive-variance").ToString(), "adaptive-variance");
  FilterConfig without_moments;
  without_moments.temporal = ParseTemporal("adaptive-variance");
  EXPECT_THROW(without_moments.Validate(), ConfigError);
}

}  // namespace
}  // namespace hpsf::testing
