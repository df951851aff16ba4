// core/shared/exact_rounding.h against the C library, on every binade a blend's sums and counts reach: the halves
// and quarters around each integer, the doubles next to them, and the edges at 2^52 and past 2^64. The GLSL side is
// held by the blend tests (temporal_blend_test.cpp), which failed with GLSL's roundEven on lavapipe on an AVX2 CPU.
#include "core/shared/exact_rounding.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace hpsf::shared {
namespace {

TEST(ExactRounding, AgreesWithTheCLibraryAroundEveryPowerOfTwo) {
  int checked = 0;
  for (int e = -3; e <= 66; ++e) {
    for (double offset : {0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.5, 3.5}) {
      const double base = std::ldexp(1.0, e) + offset;
      for (double x : {base, std::nextafter(base, 0.0), std::nextafter(base, HUGE_VAL)}) {
        EXPECT_EQ(RoundHalfEvenNonNegative(x), std::nearbyint(x)) << x;
        EXPECT_EQ(CeilNonNegative(x), std::ceil(x)) << x;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 70 * 8 * 3);
}

TEST(ExactRounding, HalvesGoToEvenAboveTwoToTheTwentyFour) {
  // The values lavapipe's fallback returned unrounded: 2^24 and above, with a fraction.
  EXPECT_EQ(RoundHalfEvenNonNegative(2807695085253715.5), 2807695085253716.0);
  EXPECT_EQ(RoundHalfEvenNonNegative(2807695085253716.5), 2807695085253716.0);
  EXPECT_EQ(RoundHalfEvenNonNegative(16777216.5), 16777216.0);
  EXPECT_EQ(RoundHalfEvenNonNegative(16777217.5), 16777218.0);
  EXPECT_EQ(CeilNonNegative(16777216.25), 16777217.0);
  EXPECT_EQ(RoundHalfEvenNonNegative(0.5), 0.0);
  EXPECT_EQ(RoundHalfEvenNonNegative(0.0), 0.0);
  EXPECT_EQ(CeilNonNegative(0.0), 0.0);
}

TEST(ExactRounding, InfinityAndNaNComeBackAsTheyAre) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(CeilNonNegative(inf), inf);
  EXPECT_EQ(RoundHalfEvenNonNegative(inf), inf);
  EXPECT_TRUE(std::isnan(CeilNonNegative(std::nan(""))));
  EXPECT_TRUE(std::isnan(RoundHalfEvenNonNegative(std::nan(""))));
}

}  // namespace
}  // namespace hpsf::shared
