// The full stored key of `--key-identity full` (NVIDIA SHaRC's 64-bit key, made of hpsf's key words): a slot
// stores the cell's whole key instead of a reduced fingerprint, so two cells never share a slot by an alias. The
// words pack into 64 bits: x, y and z in 17 bits each (two's complement, cells -2^16 .. 2^16 - 1), the level word
// (l' + 128, 1..256) in 9 bits and the normal bucket in 3; the extra word must be 0. A cell outside those ranges
// has no full key and is unkeyable (core/shared/key.h). Since the level word is never 0, the high word is never 0:
// no key equals the empty tag 0 or priority eviction's tombstone 0xFFFFFFFF.
#ifndef HPSF_CORE_SHARED_FULL_KEY_H
#define HPSF_CORE_SHARED_FULL_KEY_H

#include "key_words.h"

HPSF_SHARED_BEGIN

const uint kIdentityFingerprint = 0u;  // KeyParams::key_identity
const uint kIdentityFull = 1u;

const uint kFullKeyCellBits = 17u;
const int kFullKeyCellMin = -65536;  // -2^16
const int kFullKeyCellMax = 65535;
const uint kFullKeyLevelWordLimit = 512u;  // 9 bits
const uint kFullKeyNormalLimit = 8u;       // 3 bits

HPSF_FN bool FullKeyCellFits(uint word) {
  int v = int(word);
  return v >= kFullKeyCellMin && v <= kFullKeyCellMax;
}

HPSF_FN bool FullKeyFits(KeyWords w) {
  return FullKeyCellFits(w.cell_x) && FullKeyCellFits(w.cell_y) && FullKeyCellFits(w.cell_z) &&
         w.level < kFullKeyLevelWordLimit && w.normal < kFullKeyNormalLimit && w.extra == 0u;
}

// Bits 0-16 x, 17-33 y, 34-50 z, 51-59 the level word, 60-62 the normal bucket, 63 zero; as (low, high) words.
HPSF_FN uvec2 FullKey(KeyWords w) {
  const uint mask = (1u << kFullKeyCellBits) - 1u;
  uint x = w.cell_x & mask;
  uint y = w.cell_y & mask;
  uint z = w.cell_z & mask;
  return uvec2(x | (y << 17u), (y >> 15u) | (z << 2u) | (w.level << 19u) | (w.normal << 28u));
}

// What a slot stores for key words: the reduced fingerprint (high word 0) or the full key. `fits` is false where a
// full key does not exist; then no record has these words and no slot holds them.
struct StoredIdentity {
  uvec2 words;  // (low, high)
  bool fits;
};

HPSF_FN StoredIdentity IdentityOfWords(KeyWords w, uint key_identity, uint fingerprint_bits) {
  StoredIdentity s;
  s.fits = key_identity != kIdentityFull || FullKeyFits(w);
  s.words = key_identity == kIdentityFull ? FullKey(w) : uvec2(Fingerprint(w, fingerprint_bits), 0u);
  return s;
}

HPSF_FN uint64_t IdentityValue(uvec2 words) { return (uint64_t(words.y) << 32) | uint64_t(words.x); }

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_FULL_KEY_H
