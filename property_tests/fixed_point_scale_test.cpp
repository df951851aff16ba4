// The per-batch choice of F never lets a channel's total reach 2^63, and is the largest F that does not; for a
// table that integrates K frames, K such totals stay below 2^63.
#include "core/fixed_point_scale.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <vector>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/shared/fixed_point.h"

namespace hpsf {
namespace {

RC_GTEST_PROP(FixedPointScale, KFramesOfTotalsStayBelowTwoToThe63AndFIsMaximal, ()) {
  const std::uint32_t frames = *rc::gen::element<std::uint32_t>(1u, 1u, 2u, 3u, 16u, 1000u, 1u << 20);
  const int exponent_spread = *rc::gen::inRange(0, 120);
  const int count = *rc::gen::inRange(1, 400);
  std::vector<Record> records;
  for (int i = 0; i < count; ++i) {
    VertexSample v;
    for (int c = 0; c < 3; ++c) {
      const float mantissa = 1.0f + float(*rc::gen::inRange(0, 1 << 23)) * 0x1p-23f;
      v.contribution[c] = *rc::gen::inRange(0, 8) == 0
                              ? 0.0f
                              : std::ldexp(mantissa, *rc::gen::inRange(-exponent_spread, exponent_spread));
    }
    records.push_back(MakeVertexRecord(v));
  }
  const int f = ChooseFixedPointBits(records, frames);
  const unsigned __int128 limit = (static_cast<unsigned __int128>(1) << 63) / frames;
  bool next_overflows = f == shared::kFixedPointBitsMax;
  for (int channel = 0; channel < 3; ++channel) {
    RC_ASSERT(FixedPointCeilingSum(records, channel, f) < limit);
    // The sums the kernels will form, with rounding half to even, stay below the bound too.
    unsigned __int128 rounded = 0;
    for (const Record& r : records) rounded += shared::ToFixedPoint(r.contribution[channel], shared::PowerOfTwo(f));
    RC_ASSERT(rounded < limit);
    if (f < shared::kFixedPointBitsMax)
      next_overflows = next_overflows || FixedPointCeilingSum(records, channel, f + 1) >= limit;
  }
  RC_ASSERT(next_overflows);
}

// The backends run F's passes on all cores: however the contributions are split into ranges, and in whatever
// order the ranges run, F is the one the whole batch gives in one range.
RC_GTEST_PROP(FixedPointScale, FDoesNotDependOnHowTheRunnerSplitsTheWork, ()) {
  const int count = *rc::gen::inRange(1, 400);
  const int exponent_spread = *rc::gen::inRange(0, 120);
  std::vector<glm::vec3> contributions;
  for (int i = 0; i < count; ++i) {
    glm::vec3 c;
    for (int k = 0; k < 3; ++k) {
      const float mantissa = 1.0f + float(*rc::gen::inRange(0, 1 << 23)) * 0x1p-23f;
      c[k] = *rc::gen::inRange(0, 8) == 0 ? 0.0f
                                          : std::ldexp(mantissa, *rc::gen::inRange(-exponent_spread, exponent_spread));
    }
    contributions.push_back(c);
  }
  const std::size_t chunk = *rc::gen::inRange<std::size_t>(1, std::size_t(count) + 1);
  const bool backwards = *rc::gen::arbitrary<bool>();
  const RangeRunner split = [&](std::size_t n, const std::function<void(std::size_t, std::size_t)>& work) {
    const std::size_t ranges = (n + chunk - 1) / chunk;
    for (std::size_t k = 0; k < ranges; ++k) {
      const std::size_t r = backwards ? ranges - 1 - k : k;
      work(r * chunk, std::min(n, (r + 1) * chunk));
    }
  };
  RC_ASSERT(ChooseFixedPointBitsOf(contributions, split) == ChooseFixedPointBitsOf(contributions));
}

// A contribution converts at F exactly when c * 2^F lies below 2^64 (undefined past it, in C++ and GLSL alike): the
// boundary is exact, and the error names the largest F that would convert the batch's largest contribution.
TEST(FixedPointScale, AContributionPastFixed64IsRefusedAtItsExactBoundary) {
  const std::vector<glm::vec3> batch = {glm::vec3(0.5f, 3.0f, 0.0f), glm::vec3(1.0f, 0.25f, 2.0f)};
  EXPECT_NO_THROW(RequireFixedPointConverts(batch, 62));  // 3 x 2^62 < 2^64
  try {
    RequireFixedPointConverts(batch, 63);  // 3 x 2^63 >= 2^64
    ADD_FAILURE() << "F 63 accepted for a contribution of 3";
  } catch (const FixedPointRangeError& e) {
    EXPECT_NE(std::string(e.what()).find("--fixed-point-bits: F 63 is too large for a contribution of 3.000000"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("F 62 at most converts it"), std::string::npos) << e.what();
  }
  const std::vector<glm::vec3> just_below = {glm::vec3(std::nextafter(2.0f, 0.0f), 0.0f, 0.0f)};
  EXPECT_NO_THROW(RequireFixedPointConverts(just_below, 63));  // (2 - 2^-23) x 2^63 < 2^64
  EXPECT_THROW(RequireFixedPointConverts(std::vector<glm::vec3>{glm::vec3(2.0f)}, 63), FixedPointRangeError);
  EXPECT_NO_THROW(RequireFixedPointConverts(std::vector<glm::vec3>{}, 126));  // nothing to convert
}

}  // namespace
}  // namespace hpsf
