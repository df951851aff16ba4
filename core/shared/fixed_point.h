// fixed64 accumulation: each non-negative channel becomes an unsigned 64-bit integer with F fraction bits,
// rounded half to even (truncation would bias every cell downwards, docs/design/defects.md, D11). The host picks F per
// batch so no channel's total can reach 2^63 (core/fixed_point_scale.h).
#ifndef HPSF_CORE_SHARED_FIXED_POINT_H
#define HPSF_CORE_SHARED_FIXED_POINT_H

#include "float_bits.h"

HPSF_SHARED_BEGIN

const int kFixedPointBitsMin = -126;  // 2^F must be a normal float
const int kFixedPointBitsMax = 126;

// scale = 2^F from PowerOfTwo(F). c * 2^F is exact in the normal range; below it the value is under 0.5 and
// rounds to 0 whether or not the device flushed it.
HPSF_FN uint64_t ToFixedPoint(float c, float scale) {
  HPSF_PRECISE float scaled = c * scale;
  return uint64_t(HPSF_ROUND_EVEN(scaled));
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_FIXED_POINT_H
