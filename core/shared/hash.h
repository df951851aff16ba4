// Integer hashes for the table and the counter RNG (Jarzynski & Olano 2020): PCG for the slot index, an
// xxHash32-style mixer with its own seed for fingerprints and random numbers. Bit operations only.
#ifndef HPSF_CORE_SHARED_HASH_H
#define HPSF_CORE_SHARED_HASH_H

#include "prelude.h"

HPSF_SHARED_BEGIN

const uint kXxPrime2 = 2246822519u;
const uint kXxPrime3 = 3266489917u;
const uint kXxPrime4 = 668265263u;
const uint kXxPrime5 = 374761393u;

// PCG-RXS-M-XS 32: one LCG step, then a random xorshift, multiply and xorshift output permutation.
HPSF_FN uint Pcg(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

HPSF_FN uint RotateLeft(uint x, uint r) { return (x << r) | (x >> (32u - r)); }

// xxHash32's per-word round and final avalanche, over a stream of 32-bit words.
HPSF_FN uint XxBegin(uint seed, uint word_count) { return seed + kXxPrime5 + word_count * 4u; }
HPSF_FN uint XxAdd(uint h, uint word) { return RotateLeft(h + word * kXxPrime3, 17u) * kXxPrime4; }
HPSF_FN uint XxFinish(uint h) {
  h = (h ^ (h >> 15u)) * kXxPrime2;
  h = (h ^ (h >> 13u)) * kXxPrime3;
  return h ^ (h >> 16u);
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_HASH_H
