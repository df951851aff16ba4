#include "core/shared/fixed_point.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "core/fixed_point_scale.h"
#include "core/record.h"

namespace hpsf {
namespace {

float Scale(int f) { return shared::PowerOfTwo(f); }

Record ContributionRecord(glm::vec3 c) {
  VertexSample v;
  v.contribution = c;
  return MakeVertexRecord(v);
}

TEST(FixedPoint, RoundsHalfToEven) {
  const int f = 4;  // 1/16 steps
  EXPECT_EQ(shared::ToFixedPoint(0.5f / 16.0f, Scale(f)), 0u);
  EXPECT_EQ(shared::ToFixedPoint(1.5f / 16.0f, Scale(f)), 2u);
  EXPECT_EQ(shared::ToFixedPoint(2.5f / 16.0f, Scale(f)), 2u);
  EXPECT_EQ(shared::ToFixedPoint(3.5f / 16.0f, Scale(f)), 4u);
  EXPECT_EQ(shared::ToFixedPoint(std::nextafter(2.5f, 3.0f) / 16.0f, Scale(f)), 3u);
  EXPECT_EQ(shared::ToFixedPoint(std::nextafter(2.5f, 2.0f) / 16.0f, Scale(f)), 2u);
  // Large values: the rounding happens in float, exact above 2^24 too.
  EXPECT_EQ(shared::ToFixedPoint(std::ldexp(1.0f, 40), Scale(20)), 1ull << 60);
}

TEST(FixedPoint, RoundTripIsExactWhenTheValueFitsTheGrid) {
  for (int f : {-20, 0, 12, 40, 100}) {
    for (float c : {0.0f, 1.0f, 0.75f, 3.0f, 1234.5f, 0.1f, 6e-8f, 3e5f}) {
      const float scaled = c * Scale(f);
      if (scaled != std::nearbyint(scaled) || scaled >= 0x1p63f) continue;
      EXPECT_EQ(FromFixedPoint(shared::ToFixedPoint(c, Scale(f)), f), double(c)) << "c = " << c << " F = " << f;
    }
  }
  // 0.1 is not on the grid at F = 12: the round trip is within half a step.
  EXPECT_NEAR(FromFixedPoint(shared::ToFixedPoint(0.1f, Scale(12)), 12), 0.1, std::ldexp(0.5, -12));
}

TEST(FixedPointScale, EmptyBatchUsesTheLargestF) { EXPECT_EQ(ChooseFixedPointBits({}), shared::kFixedPointBitsMax); }

TEST(FixedPointScale, ChannelTotalsStayBelowTwoToThe63AndFIsMaximal) {
  std::vector<Record> records;
  for (int i = 0; i < 1000; ++i) records.push_back(ContributionRecord(glm::vec3(17.0f + i, 0.001f * i, 1e-6f)));
  const int f = ChooseFixedPointBits(records);
  for (int channel = 0; channel < 3; ++channel) {
    EXPECT_LT(FixedPointCeilingSum(records, channel, f), (unsigned __int128)1 << 63);
  }
  // One more fraction bit would overflow the red channel's bound: sum is about 518500 < 2^19.
  EXPECT_GE(FixedPointCeilingSum(records, 0, f + 1), (unsigned __int128)1 << 63);
  EXPECT_EQ(f, 63 - 19);
}

TEST(FixedPointScale, HugeContributionsGetNegativeF) {
  std::vector<Record> records(4, ContributionRecord(glm::vec3(std::numeric_limits<float>::max(), 0.0f, 0.0f)));
  const int f = ChooseFixedPointBits(records);
  EXPECT_LT(f, -60);
  EXPECT_LT(FixedPointCeilingSum(records, 0, f), (unsigned __int128)1 << 63);
  EXPECT_GE(FixedPointCeilingSum(records, 0, f + 1), (unsigned __int128)1 << 63);
}

TEST(FixedPointScale, RejectedAndVertexlessRecordsDoNotCount) {
  std::vector<Record> records = {ContributionRecord(glm::vec3(1.0f)), MakeRecordWithoutVertex(0, 0, glm::vec3(1e30f)),
                                 ContributionRecord(glm::vec3(std::numeric_limits<float>::infinity()))};
  EXPECT_EQ(ChooseFixedPointBits(records), ChooseFixedPointBits(std::span(records).first(1)));
}

}  // namespace
}  // namespace hpsf
