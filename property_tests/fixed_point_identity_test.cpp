// fixed64 conversion on the device equals the C++ conversion bit for bit: round half to even at ties, exact
// above 2^24, zero for values whose scaled form is below the normal range.
#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/shared/fixed_point.h"
#include "property_tests/vulkan_test_devices.h"
#include "vulkan/fixed_point_pass.h"

namespace hpsf {
namespace {

void ExpectIdentical(const std::vector<float>& values, int fraction_bits) {
  for (const StagingPolicy staging : testing::kStagingPolicies) {
    const std::vector<std::uint64_t> device = ToFixedPointOnDevice(testing::TestDevice(staging), values, fraction_bits);
    ASSERT_EQ(device.size(), values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::uint64_t host = shared::ToFixedPoint(values[i], shared::PowerOfTwo(fraction_bits));
      ASSERT_EQ(device[i], host) << "value " << values[i] << " F " << fraction_bits << ", --vk-staging "
                                 << ToString(staging);
    }
  }
}

TEST(FixedPointIdentity, TiesRoundToEvenOnTheDevice) {
  std::vector<float> ties;
  for (int k = 0; k < 4096; ++k) ties.push_back((k + 0.5f) / 16.0f);  // every one a tie at F = 4
  ExpectIdentical(ties, 4);
  const std::vector<std::uint64_t> device = ToFixedPointOnDevice(testing::TestDevice(StagingPolicy::kAuto), ties, 4);
  for (int k = 0; k < 4096; ++k) EXPECT_EQ(device[k] % 2, 0u) << "tie " << k << " did not round to even";
}

RC_GTEST_PROP(FixedPointIdentity, AnyNonNegativeFloatAtAnyF, ()) {
  const int fraction_bits = *rc::gen::inRange(-126, 127);
  const auto bits = *rc::gen::container<std::vector<std::uint32_t>>(256, rc::gen::arbitrary<std::uint32_t>());
  std::vector<float> values;
  for (std::uint32_t b : bits) {
    float v = std::bit_cast<float>(b & 0x7FFFFFFFu);  // non-negative
    // Keep the scaled value below 2^63, the range fixed64 guarantees, and finite.
    if (!std::isfinite(v) || std::ldexp(double(v), fraction_bits) >= 0x1p63)
      v = std::ldexp(1.5f, std::min(30 - fraction_bits, 127));
    values.push_back(v);
  }
  for (const StagingPolicy staging : testing::kStagingPolicies) {
    const std::vector<std::uint64_t> device = ToFixedPointOnDevice(testing::TestDevice(staging), values, fraction_bits);
    for (std::size_t i = 0; i < values.size(); ++i) {
      RC_ASSERT(device[i] == shared::ToFixedPoint(values[i], shared::PowerOfTwo(fraction_bits)));
    }
  }
}

}  // namespace
}  // namespace hpsf
