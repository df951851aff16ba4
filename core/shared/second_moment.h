// Per-cell second moments (--second-moments on), written once for C++ and GLSL: besides its three channel sums, a
// slot keeps the sum of its records' squared brightness y^2, y = r + g + b, from which a cell's variance follows
// (Schipek §4.1, the variance that survival, interpolation and path graphs read).
//
// fixed64 keeps the squares as a 64-bit integer at a scale of its own, 2^G (core/fixed_point_scale.h chooses G as it
// chooses F): y = r + g + b and y * y in double, each correctly rounded, times 2^G (exact), rounded half to even by
// hand (core/shared/exact_rounding.h). Every step is correctly rounded, so every backend adds the same integer. float32
// keeps a float sum of float squares: y and y * y in float, flushed like the key path, so a device's denormal mode
// cannot change a term.
#ifndef HPSF_CORE_SHARED_SECOND_MOMENT_H
#define HPSF_CORE_SHARED_SECOND_MOMENT_H

#include "exact_rounding.h"
#include "float_bits.h"

HPSF_SHARED_BEGIN

// y = r + g + b of a contribution, in double: two correctly rounded adds.
HPSF_FN double Brightness(vec3 c) {
  HPSF_PRECISE double partial = double(c.x) + double(c.y);
  HPSF_PRECISE double y = partial + double(c.z);
  return y;
}

// fixed64: round(y^2 * 2^G), the integer a record adds to its slot's square sum. square_scale = 2^G; the host keeps
// the product below 2^64 (RequireSquaresConvert).
HPSF_FN uint64_t SquareToFixedPoint(vec3 c, double square_scale) {
  HPSF_PRECISE double y = Brightness(c);
  HPSF_PRECISE double square = y * y;
  HPSF_PRECISE double scaled = square * square_scale;
  return uint64_t(RoundHalfEvenNonNegative(scaled));
}

// float32: the float a record adds to its slot's square sum.
HPSF_FN float SquareAsFloat(vec3 c) {
  HPSF_PRECISE float partial = Flush(c.x + c.y);
  HPSF_PRECISE float y = Flush(partial + c.z);
  HPSF_PRECISE float square = Flush(y * y);
  return square;
}

// The variance of a cell's channel mean m = y / 3 from the means of y and y^2 over its samples: (E[y^2] - E[y]^2) / 9,
// never negative. In double, its error is a few units of E[y^2]'s last place: exact enough for fixed64's exact sums.
// (The same difference in float32, the rounding of both means amplified by the cancellation, would be far worse:
// docs/design/algorithm.md#second-moments.)
HPSF_FN double CellVariance(double mean_brightness, double mean_square) {
  HPSF_PRECISE double squared_mean = mean_brightness * mean_brightness;
  HPSF_PRECISE double difference = mean_square - squared_mean;
  HPSF_PRECISE double variance = difference / double(9.0);
  return variance > double(0.0) ? variance : double(0.0);
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_SECOND_MOMENT_H
