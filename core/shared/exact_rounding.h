// Rounding a non-negative double to an integer by exact operations only, shared by C++ and GLSL. GLSL's roundEven,
// ceil, floor and trunc on doubles cannot be trusted: Mesa lavapipe 22.3 on an AVX2 CPU returned doubles above
// 2^24 from roundEven unrounded (docs/design/vulkan.md#doubles-are-rounded-by-hand). A conversion to uint64
// truncates exactly on every backend, and below 2^52 a double minus its truncation is exact, so these give the
// correctly rounded integer everywhere.
#ifndef HPSF_CORE_SHARED_EXACT_ROUNDING_H
#define HPSF_CORE_SHARED_EXACT_ROUNDING_H

#include "prelude.h"

HPSF_SHARED_BEGIN

// 2^52: every double at or above it is an integer.
const double kIntegralDoubles = double(4503599627370496.0);

// x rounded to the nearest integer, half to even (GLSL's roundEven, C's nearbyint in the default mode), for x >= 0;
// +inf and NaN come back as they are.
HPSF_FN double RoundHalfEvenNonNegative(double x) {
  if (!(x < kIntegralDoubles)) return x;
  uint64_t t = uint64_t(x);
  HPSF_PRECISE double fraction = x - double(t);
  bool up = fraction > double(0.5) || (fraction == double(0.5) && (t & uint64_t(1)) == uint64_t(1));
  return double(up ? t + uint64_t(1) : t);
}

// The smallest integer not below x (ceil), for x >= 0; +inf and NaN come back as they are.
HPSF_FN double CeilNonNegative(double x) {
  if (!(x < kIntegralDoubles)) return x;
  uint64_t t = uint64_t(x);
  return double(t) < x ? double(t + uint64_t(1)) : double(t);
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_EXACT_ROUNDING_H
