// The key of a cell as six 32-bit words, and the two hashes of it: the index hash that picks the first slot of
// the probe window and the fingerprint stored as the slot's tag (never 0, which marks an empty slot).
#ifndef HPSF_CORE_SHARED_KEY_WORDS_H
#define HPSF_CORE_SHARED_KEY_WORDS_H

#include "hash.h"

HPSF_SHARED_BEGIN

const uint kLevelWordBias = 128u;
const uint kIndexHashSeed = 0x9E3779B9u;
const uint kFingerprintSeed = 0x85EBCA77u;

struct KeyWords {
  uint cell_x;  // int32 cell coordinates as bit patterns
  uint cell_y;
  uint cell_z;
  uint level;   // l' + 128
  uint normal;  // normal bucket
  uint extra;   // 0; reserved for glossy and layer keys
};

// Both hashes absorb the six words with xxHash32's round, from different seeds, as two independent chains a
// CPU or GPU overlaps (the cell words last, since they are known last); the index hash then ends in a PCG
// permutation, the fingerprint in xxHash32's avalanche. With normal_in_index 0 the bucket only enters the fingerprint,
// so records with different normals share a window and probing searches similar normals (Binder et al. §3.2.2).
HPSF_FN uint AbsorbKeyWords(uint seed, KeyWords k, uint normal) {
  uint h = XxBegin(seed, 6u);
  h = XxAdd(h, normal);
  h = XxAdd(h, k.extra);
  h = XxAdd(h, k.level);
  h = XxAdd(h, k.cell_x);
  h = XxAdd(h, k.cell_y);
  return XxAdd(h, k.cell_z);
}

HPSF_FN uint IndexHash(KeyWords k, uint normal_in_index) {
  return Pcg(AbsorbKeyWords(kIndexHashSeed, k, normal_in_index != 0u ? k.normal : 0u));
}

HPSF_FN uint FullFingerprint(KeyWords k) { return XxFinish(AbsorbKeyWords(kFingerprintSeed, k, k.normal)); }

// The top `bits` bits (8..32) of a full fingerprint; 0 becomes 1, since 0 is the empty-slot tag.
HPSF_FN uint ReduceFingerprint(uint full, uint bits) {
  uint f = full >> (32u - bits);
  return f == 0u ? 1u : f;
}

HPSF_FN uint Fingerprint(KeyWords k, uint bits) { return ReduceFingerprint(FullFingerprint(k), bits); }

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_KEY_WORDS_H
