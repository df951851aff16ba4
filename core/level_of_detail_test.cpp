#include "core/shared/level_of_detail.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace hpsf::shared {
namespace {

TEST(LevelOfDetail, ExactAtJustBelowAndJustAboveEveryPowerOfTwo) {
  for (int l = kMinLevel; l <= kMaxLevel; ++l) {
    const float w = std::ldexp(1.0f, l);
    EXPECT_EQ(LevelFromWidth(w, kMinLevel, kMaxLevel), l) << "w = 2^" << l;
    EXPECT_EQ(LevelFromWidth(std::nextafter(w, 1e38f), kMinLevel, kMaxLevel), l) << "just above 2^" << l;
    // Just below 2^-126 is the largest denormal, which also maps to the minimum level.
    EXPECT_EQ(LevelFromWidth(std::nextafter(w, 0.0f), kMinLevel, kMaxLevel), std::max(l - 1, kMinLevel))
        << "just below 2^" << l;
  }
}

TEST(LevelOfDetail, ZeroAndDenormalsGiveTheMinimumLevel) {
  for (float w : {0.0f, -0.0f, std::numeric_limits<float>::denorm_min(),
                  std::nextafter(std::numeric_limits<float>::min(), 0.0f)}) {
    EXPECT_EQ(LevelFromWidth(w, kMinLevel, kMaxLevel), kMinLevel) << w;
    EXPECT_EQ(LevelFromWidth(w, -5, 7), -5) << w;
  }
}

TEST(LevelOfDetail, ClampsToTheConfiguredRange) {
  EXPECT_EQ(LevelFromWidth(std::ldexp(1.0f, 127), kMinLevel, kMaxLevel), kMaxLevel);
  EXPECT_EQ(LevelFromWidth(std::numeric_limits<float>::infinity(), kMinLevel, kMaxLevel), kMaxLevel);
  EXPECT_EQ(LevelFromWidth(1024.0f, -5, 7), 7);
  EXPECT_EQ(LevelFromWidth(0.001f, -5, 7), -5);
  EXPECT_EQ(LevelFromWidth(3.0f, -5, 7), 1);
}

TEST(LevelOfDetail, PathLengthUsesTheLInfinityNormOfTheLastSegment) {
  EXPECT_EQ(PathLength(10.0f, vec3(1.0f, -7.0f, 2.0f), vec3(0.0f, 0.0f, 0.0f)), 17.0f);
  EXPECT_EQ(PathLength(0.0f, vec3(-3.0f, 1.0f, 1.0f), vec3(2.0f, 0.0f, 0.0f)), 5.0f);
  EXPECT_EQ(PathLength(0.5f, vec3(1.0f), vec3(1.0f)), 0.5f);
}

TEST(LevelOfDetail, LevelOfTheFootprint) {
  // w = 0.25 * 8 = 2 exactly: level 1; one ulp less: level 0.
  EXPECT_EQ(LevelOfDetail(0.25f, 8.0f, kMinLevel, kMaxLevel), 1);
  EXPECT_EQ(LevelOfDetail(0.25f, std::nextafter(8.0f, 0.0f), kMinLevel, kMaxLevel), 0);
  EXPECT_EQ(LevelOfDetail(1e-30f, 1e-20f, kMinLevel, kMaxLevel), kMinLevel);  // product is denormal
}

}  // namespace
}  // namespace hpsf::shared
