// The per-batch choice of F never lets a channel's total reach 2^63, and is the largest F that does not.
#include <bit>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/fixed_point_scale.h"
#include "core/shared/fixed_point.h"

namespace hpsf {
namespace {

RC_GTEST_PROP(FixedPointScale, TotalsStayBelowTwoToThe63AndFIsMaximal, ()) {
  const int exponent_spread = *rc::gen::inRange(0, 120);
  const int count = *rc::gen::inRange(1, 400);
  std::vector<Record> records;
  for (int i = 0; i < count; ++i) {
    VertexSample v;
    for (int c = 0; c < 3; ++c) {
      const float mantissa = 1.0f + float(*rc::gen::inRange(0, 1 << 23)) * 0x1p-23f;
      v.contribution[c] = *rc::gen::inRange(0, 8) == 0 ? 0.0f : std::ldexp(mantissa, *rc::gen::inRange(-exponent_spread, exponent_spread));
    }
    records.push_back(MakeVertexRecord(v));
  }
  const int f = ChooseFixedPointBits(records);
  const unsigned __int128 limit = static_cast<unsigned __int128>(1) << 63;
  bool next_overflows = f == shared::kFixedPointBitsMax;
  for (int channel = 0; channel < 3; ++channel) {
    RC_ASSERT(FixedPointCeilingSum(records, channel, f) < limit);
    // The sums the kernels will form, with rounding half to even, stay below the bound too.
    unsigned __int128 rounded = 0;
    for (const Record& r : records) rounded += shared::ToFixedPoint(r.contribution[channel], shared::PowerOfTwo(f));
    RC_ASSERT(rounded < limit);
    if (f < shared::kFixedPointBitsMax) next_overflows = next_overflows || FixedPointCeilingSum(records, channel, f + 1) >= limit;
  }
  RC_ASSERT(next_overflows);
}

}  // namespace
}  // namespace hpsf
