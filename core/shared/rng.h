// The counter RNG: every random number is a pure function of (seed, frame, pixel, sample, bounce, dimension),
// so results never depend on thread count or order. Floats take the top 24 bits: exact, in [0, 1).
#ifndef HPSF_CORE_SHARED_RNG_H
#define HPSF_CORE_SHARED_RNG_H

#include "hash.h"

HPSF_SHARED_BEGIN

const uint kRngSeedSalt = 0x52A7C0DEu;

// Dimensions the filter reserves, far above any the tracer uses for its own sampling.
const uint kJitterDimensionU = 0xFFFF0000u;
const uint kJitterDimensionV = 0xFFFF0001u;

struct RngCounter {
  uint seed;
  uint frame;
  uint pixel;
  uint sample_index;
  uint bounce;
};

// The counter's five words absorbed once; each dimension then costs one round and the avalanche.
HPSF_FN uint RngPrefix(RngCounter c) {
  uint h = XxBegin(c.seed ^ kRngSeedSalt, 6u);
  h = XxAdd(h, c.frame);
  h = XxAdd(h, c.pixel);
  h = XxAdd(h, c.sample_index);
  return XxAdd(h, c.bounce);
}

HPSF_FN uint RandomBitsFromPrefix(uint prefix, uint dimension) { return XxFinish(XxAdd(prefix, dimension)); }

HPSF_FN uint RandomBits(RngCounter c, uint dimension) { return RandomBitsFromPrefix(RngPrefix(c), dimension); }

// (r >> 8) * 2^-24: both factors exact, so the product is exact.
HPSF_FN float BitsToUnitFloat(uint r) {
  HPSF_PRECISE float u = float(r >> 8u) * 5.9604644775390625e-8f;
  return u;
}

HPSF_FN float RandomFloat(RngCounter c, uint dimension) { return BitsToUnitFloat(RandomBits(c, dimension)); }
HPSF_FN float RandomFloatFromPrefix(uint prefix, uint dimension) {
  return BitsToUnitFloat(RandomBitsFromPrefix(prefix, dimension));
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_RNG_H
