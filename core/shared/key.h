// The whole key path of one record, written once for C++ and GLSL: path length, level, jitter, level again,
// cell, key words, first slot and fingerprint. keys.comp runs exactly this; so does every C++ backend.
#ifndef HPSF_CORE_SHARED_KEY_H
#define HPSF_CORE_SHARED_KEY_H

#include "cell.h"
#include "full_key.h"
#include "jitter.h"
#include "key_params.h"
#include "key_words.h"
#include "level_of_detail.h"
#include "normal_bucket.h"
#include "record_layout.h"
#include "rng.h"

HPSF_SHARED_BEGIN

const uint kKeyed = 0u;
const uint kKeyNoVertex = 1u;   // sky hit or path ended: the record carries radiance_before only
const uint kKeyUnkeyable = 2u;  // |q| >= 2^31 in some axis: falls back to its own contribution

// 48 bytes, so a shader writes it as three 16-byte vectors (lavapipe stores per lane and per store).
// What a slot stores for the key (its identity) is (identity_high << 32) | fingerprint: the reduced fingerprint
// with --key-identity fingerprint (identity_high 0), the full key's two words with full (core/shared/full_key.h).
struct KeyResult {
  KeyWords words;
  uint slot0;
  uint fingerprint;    // the identity's low word
  int level;           // l' after jitter (the fixed level of the cell size with level of detail off)
  uint status;         // kKeyed, kKeyNoVertex or kKeyUnkeyable
  uint identity_high;  // the identity's high word: 0 with a fingerprint
  uint padding1;       // always 0
};

HPSF_FN KeyResult EmptyKeyResult(uint status) {
  KeyResult k;
  k.words.cell_x = 0u;
  k.words.cell_y = 0u;
  k.words.cell_z = 0u;
  k.words.level = 0u;
  k.words.normal = 0u;
  k.words.extra = 0u;
  k.slot0 = 0u;
  k.fingerprint = 0u;
  k.level = 0;
  k.status = status;
  k.identity_high = 0u;
  k.padding1 = 0u;
  return k;
}

HPSF_FN RngCounter JitterCounter(KeyParams p, Record r) {
  RngCounter c;
  c.seed = p.seed;
  c.frame = p.frame;
  c.pixel = RecordPixel(r);
  c.sample_index = RecordSample(r);
  c.bounce = RecordBounce(r);
  return c;
}

// Where a record's key is taken: its jittered position, the level of its cell and 1 / the cell's size. The resolve's
// neighbourhood search (core/shared/neighbour_search.h) reads it again for a record whose cell has few samples.
struct KeyPosition {
  vec3 jittered;
  int level;           // l' after jitter (the fixed level of the cell size with level of detail off)
  float inverse_size;  // 2^-l' under level of detail, else the host's 1 / cell_size
};

HPSF_FN KeyPosition JitteredKeyPosition(KeyParams p, Record r) {
  vec3 x = vec3(r.position);
  vec3 x_prev = vec3(r.previous);
  float d_prefix = r.position.w;
  uint rng = RngPrefix(JitterCounter(p, r));
  float u1 = RandomFloatFromPrefix(rng, kJitterDimensionU);
  float u2 = RandomFloatFromPrefix(rng, kJitterDimensionV);

  // Both modes run one straight line, every value computed and then selected, with no branch on
  // lod_enabled: a SIMD device executing a branch under a mask pays for both sides (and the jitter twice).
  bool lod = p.lod_enabled != 0u;
  int level_before = LevelOfDetail(p.footprint_scale, PathLength(d_prefix, x, x_prev), p.level_min, p.level_max);
  float cell_before = PowerOfTwo(level_before);
  float cell_size = lod ? cell_before : p.cell_size;
  HPSF_PRECISE float amplitude = Flush(p.jitter_scale * cell_size);
  KeyPosition at;
  at.jittered = JitterInTangentPlane(x, vec3(r.tangent), vec3(r.bitangent), amplitude, u1, u2);
  // The level is recomputed after the jitter (docs/design/defects.md, D5): the cell must match the jittered position.
  int level_after =
      LevelOfDetail(p.footprint_scale, PathLength(d_prefix, at.jittered, x_prev), p.level_min, p.level_max);
  int level_fixed = UnbiasedExponent(p.cell_size);
  at.level = lod ? level_after : level_fixed;
  float inverse_after = PowerOfTwo(-level_after);
  at.inverse_size = lod ? inverse_after : p.inverse_cell_size;
  return at;
}

// The key of a record with a vertex, from its position (JitteredKeyPosition's).
HPSF_FN KeyResult KeyAtPosition(KeyParams p, Record r, KeyPosition at) {
  int level = at.level;
  Cell cell = CellOf(at.jittered, at.inverse_size);
  KeyWords words;
  words.cell_x = uint(cell.index.x);
  words.cell_y = uint(cell.index.y);
  words.cell_z = uint(cell.index.z);
  words.level = uint(level + int(kLevelWordBias));
  words.normal = NormalBucket(p, r);
  words.extra = 0u;
  StoredIdentity identity = IdentityOfWords(words, p.key_identity, p.fingerprint_bits);
  // A cell beyond the full key's 17 bits has no identity: unkeyable, as one beyond int32 is.
  if (!cell.keyable || !identity.fits) {
    KeyResult unkeyable = EmptyKeyResult(kKeyUnkeyable);
    unkeyable.level = level;
    return unkeyable;
  }

  KeyResult k;
  k.words = words;
  k.slot0 = IndexHash(k.words, p.normal_in_index) & p.capacity_mask;
  k.fingerprint = identity.words.x;
  k.level = level;
  k.status = kKeyed;
  k.identity_high = identity.words.y;
  k.padding1 = 0u;
  return k;
}

HPSF_FN KeyResult ComputeKey(KeyParams p, Record r) {
  if (!RecordHasVertex(r)) return EmptyKeyResult(kKeyNoVertex);
  return KeyAtPosition(p, r, JitteredKeyPosition(p, r));
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_KEY_H
