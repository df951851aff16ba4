// Tangent-plane jitter of the filter vertex (Binder et al. §3.1, Algorithm 1), evaluated in exactly the order
// docs/design/key-path.md fixes: x' = x + (jitter_scale * 2^l) * ((2 u1 - 1) * T + (2 u2 - 1) * B).
#ifndef HPSF_CORE_SHARED_JITTER_H
#define HPSF_CORE_SHARED_JITTER_H

#include "float_bits.h"

HPSF_SHARED_BEGIN

// amplitude = jitter_scale * cell size; u1, u2 in [0, 1) with 24 bits, so 2u - 1 is exact.
HPSF_FN vec3 JitterInTangentPlane(vec3 x, vec3 tangent, vec3 bitangent, float amplitude, float u1, float u2) {
  HPSF_PRECISE float a = 2.0f * u1 - 1.0f;
  HPSF_PRECISE float b = 2.0f * u2 - 1.0f;
  HPSF_PRECISE vec3 offset = Flush(Flush(a * tangent) + Flush(b * bitangent));
  HPSF_PRECISE vec3 jittered = Flush(x + Flush(amplitude * offset));
  return jittered;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_JITTER_H
