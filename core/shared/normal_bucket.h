// The normal part of a key: none, the octant from the three sign bits (so -0.0 and +0.0 differ), or an
// octahedral cell whose 16-bit coordinates per axis the host computed and stored in the record.
#ifndef HPSF_CORE_SHARED_NORMAL_BUCKET_H
#define HPSF_CORE_SHARED_NORMAL_BUCKET_H

#include "key_params.h"
#include "record_layout.h"

HPSF_SHARED_BEGIN

HPSF_FN uint SignOctant(vec3 n) {
  return (floatBitsToUint(n.x) >> 31u) | ((floatBitsToUint(n.y) >> 31u) << 1u) | ((floatBitsToUint(n.z) >> 31u) << 2u);
}

// The top `bits` bits of each 16-bit octahedral coordinate.
HPSF_FN uint OctahedralBucket(uint packed_uv, uint bits) {
  uint shift = 16u - bits;
  uint u = (packed_uv & 0xFFFFu) >> shift;
  uint v = (packed_uv >> 16u) >> shift;
  return u | (v << bits);
}

HPSF_FN uint NormalBucket(KeyParams p, Record r) {
  if (p.normal_mode == kNormalSign) return SignOctant(vec3(r.normal));
  if (p.normal_mode == kNormalOctahedral) return OctahedralBucket(r.path.w, p.normal_bits);
  return 0u;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_NORMAL_BUCKET_H
