// The part of FilterConfig that the key path reads, as one block of 32-bit scalars (a push-constant block in
// GLSL). The host fills it from a validated FilterConfig; nothing here is computed on the device.
#ifndef HPSF_CORE_SHARED_KEY_PARAMS_H
#define HPSF_CORE_SHARED_KEY_PARAMS_H

#include "prelude.h"

HPSF_SHARED_BEGIN

const uint kNormalNone = 0u;
const uint kNormalSign = 1u;
const uint kNormalOctahedral = 2u;

struct KeyParams {
  float footprint_scale;    // filter_width_px * 2 tan(fov_y / 2) / image_height: w = footprint_scale * d
  float jitter_scale;       // jitter amplitude in units of the cell size
  float cell_size;          // level of detail off: the cell edge
  float inverse_cell_size;  // level of detail off: 1 / cell_size, correctly rounded on the host
  int level_min;            // clamp of the level, inside [-126, 126]
  int level_max;
  uint lod_enabled;       // 1: cell size 2^l from the footprint; 0: cell_size
  uint normal_mode;       // kNormalNone, kNormalSign or kNormalOctahedral
  uint normal_bits;       // octahedral: bits per axis, 1..16
  uint normal_in_index;   // 1: the normal bucket enters the index hash; 0: only the fingerprint
  uint capacity_mask;     // capacity - 1, capacity a power of two
  uint fingerprint_bits;  // 8..32
  uint seed;
  uint frame;
  uint record_count;
  uint key_identity;  // kIdentityFingerprint or kIdentityFull (core/shared/full_key.h): what a slot stores
};

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_KEY_PARAMS_H
