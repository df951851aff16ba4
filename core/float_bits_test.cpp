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

// Flush is written with a C++-only signed zero (std::copysign) beside the GLSL bit mask; both must be the bit
// definition: exponent 0 keeps only the sign bit, anything else is unchanged. Every denormal and zero pattern,
// and a stride through all the others (NaNs and infinities included).
TEST(FloatBits, FlushIsTheBitDefinitionForEveryDenormalAndASweepOfTheRest) {
  std::uint64_t wrong = 0;
  uint first_wrong = 0;
  auto check = [&](uint bits) {
    const uint expected = (bits & kExponentMask) == 0u ? bits & kSignBit : bits;
    if (std::bit_cast<uint>(Flush(std::bit_cast<float>(bits))) != expected && wrong++ == 0) first_wrong = bits;
  };
  for (uint mantissa = 0; mantissa < (1u << 23); ++mantissa) {
    check(mantissa);
    check(kSignBit | mantissa);
  }
  for (std::uint64_t bits = 0; bits <= 0xFFFFFFFFu; bits += 4099) check(static_cast<uint>(bits));
  check(0x7F800000u);  // +Inf
  check(0xFFC00001u);  // a negative NaN with payload
  EXPECT_EQ(wrong, 0u) << "first wrong input bits: 0x" << std::hex << first_wrong;
}

// GLSL's abs clears the sign bit; the C++ side must too (glm's keeps -0.0).
TEST(FloatBits, AbsClearsTheSignBitAsGlslDoes) {
  for (float x : {-0.0f, -std::numeric_limits<float>::denorm_min(), -1.5f, -std::numeric_limits<float>::infinity()}) {
    EXPECT_EQ(std::bit_cast<uint>(abs(x)), std::bit_cast<uint>(x) & ~kSignBit) << x;
    const vec3 v = abs(vec3(x, -x, x));
    EXPECT_EQ(std::bit_cast<uint>(v.y), std::bit_cast<uint>(-x) & ~kSignBit);
    EXPECT_FALSE(std::signbit(v.x) || std::signbit(v.y) || std::signbit(v.z));
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
