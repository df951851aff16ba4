#include "core/shared/float_bits.h"

#include <bit>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace hpsf::shared {
namespace {

TEST(FloatBits, PowerOfTwoIsExactForEveryLevel) {
  for (int l = -126; l <= 127; ++l) {
    EXPECT_EQ(PowerOfTwo(l), std::ldexp(1.0f, l)) << "l = " << l;
    EXPECT_EQ(UnbiasedExponent(PowerOfTwo(l)), l) << "l = " << l;
  }
}

TEST(FloatBits, UnbiasedExponentOfSpecialValues) {
  EXPECT_EQ(UnbiasedExponent(0.0f), -127);
  EXPECT_EQ(UnbiasedExponent(-0.0f), -127);
  EXPECT_EQ(UnbiasedExponent(std::numeric_limits<float>::denorm_min()), -127);
  EXPECT_EQ(UnbiasedExponent(std::numeric_limits<float>::infinity()), 128);
  EXPECT_EQ(UnbiasedExponent(-3.0f), 1);
}

TEST(FloatBits, FlushTurnsDenormalsIntoSignedZero) {
  const float tiny = std::numeric_limits<float>::denorm_min();
  const float largest_denormal = std::nextafter(std::numeric_limits<float>::min(), 0.0f);
  for (float d : {tiny, largest_denormal}) {
    EXPECT_EQ(std::bit_cast<uint>(Flush(d)), 0u);
    EXPECT_EQ(std::bit_cast<uint>(Flush(-d)), kSignBit);
  }
  for (float x : {std::numeric_limits<float>::min(), -std::numeric_limits<float>::min(), 1.5f, -0.0f, 0.0f, 1e38f}) {
    EXPECT_EQ(std::bit_cast<uint>(Flush(x)), std::bit_cast<uint>(x));
  }
}

TEST(FloatBits, ClassifiesNonFiniteAndNegativeByBits) {
  EXPECT_TRUE(IsNonFinite(std::numeric_limits<float>::infinity()));
  EXPECT_TRUE(IsNonFinite(-std::numeric_limits<float>::infinity()));
  EXPECT_TRUE(IsNonFinite(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_FALSE(IsNonFinite(std::numeric_limits<float>::max()));
  EXPECT_TRUE(IsNegative(-1e-45f));
  EXPECT_FALSE(IsNegative(-0.0f));
  EXPECT_FALSE(IsNegative(0.0f));
}

}  // namespace
}  // namespace hpsf::shared
