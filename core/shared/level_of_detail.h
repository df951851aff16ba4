// Path length in the L-infinity norm and the level of detail read from the exponent bits of the footprint
// (Meijer, Algorithm 3): no sqrt, no log2, only exact or correctly rounded operations.
#ifndef HPSF_CORE_SHARED_LEVEL_OF_DETAIL_H
#define HPSF_CORE_SHARED_LEVEL_OF_DETAIL_H

#include "float_bits.h"

HPSF_SHARED_BEGIN

// d = d_prefix + max|x - x_prev|, componentwise abs.
HPSF_FN float PathLength(float d_prefix, vec3 x, vec3 x_prev) {
  HPSF_PRECISE vec3 delta = abs(Flush(x - x_prev));
  HPSF_PRECISE float d = Flush(d_prefix + max(delta.x, max(delta.y, delta.z)));
  return d;
}

// l with 2^l <= w < 2^(l+1), clamped to [level_min, level_max]; zero and denormal w give level_min, Inf gives
// level_max.
HPSF_FN int LevelFromWidth(float w, int level_min, int level_max) {
  return clamp(UnbiasedExponent(w), level_min, level_max);
}

HPSF_FN int LevelOfDetail(float footprint_scale, float d, int level_min, int level_max) {
  HPSF_PRECISE float w = Flush(footprint_scale * d);
  return LevelFromWidth(w, level_min, level_max);
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_LEVEL_OF_DETAIL_H
