// The hash maps of the HashCache's levels (Roth et al. §3.1): cuckoo hashing after Alcantara et al., a key in one of
// its `functions` candidate slots, h_i(k) = ((a_i k + b_i) mod p) mod size with p = 2^32 - 5, the largest prime below
// 2^32, and the constants a_i in [1, p), b_i in [0, p) drawn from the counter RNG for each attempt. A key is a cell of
// one level, its index packed x | y << n | z << 2n (n the level's cells per axis, log 2, at most 10), so no key reaches
// kCuckooEmpty.
#ifndef HPSF_CORE_SHARED_CUCKOO_H
#define HPSF_CORE_SHARED_CUCKOO_H

#include "prelude.h"
#include "rng.h"

HPSF_SHARED_BEGIN

const uint kCuckooEmpty = 0xFFFFFFFFu;
const uint kCuckooPrime = 4294967291u;
const uint kMaxCuckooFunctions = 4u;

struct CuckooParams {
  uint size;       // slots
  uint functions;  // candidate slots per key, 2 to kMaxCuckooFunctions
  uint a0;
  uint b0;
  uint a1;
  uint b1;
  uint a2;
  uint b2;
  uint a3;
  uint b3;
};

HPSF_FN uint CuckooKey(int x, int y, int z, int cells_log2) {
  return uint(x) | (uint(y) << uint(cells_log2)) | (uint(z) << uint(2 * cells_log2));
}

// Candidate i of `key`: exact in 64-bit integers (a_i k + b_i < 2^64).
HPSF_FN uint CuckooSlot(CuckooParams p, uint i, uint key) {
  uint a = i == 0u ? p.a0 : (i == 1u ? p.a1 : (i == 2u ? p.a2 : p.a3));
  uint b = i == 0u ? p.b0 : (i == 1u ? p.b1 : (i == 2u ? p.b2 : p.b3));
  uint64_t h = (uint64_t(a) * uint64_t(key) + uint64_t(b)) % uint64_t(kCuckooPrime);
  return uint(h % uint64_t(p.size));
}

// Where a key evicted from `slot` goes next: the candidate after the first of its candidates that is `slot`
// (Alcantara et al.'s rule; a key whose candidates coincide moves to the next one that differs, or stays).
HPSF_FN uint CuckooNextSlot(CuckooParams p, uint key, uint slot) {
  uint placed = 0u;
  for (uint i = 0u; i < p.functions; ++i) {
    if (CuckooSlot(p, i, key) == slot) {
      placed = i;
      break;
    }
  }
  for (uint step = 1u; step < p.functions; ++step) {
    uint next = CuckooSlot(p, (placed + step) % p.functions, key);
    if (next != slot) return next;
  }
  return slot;
}

// The constants of attempt `attempt` at `level` for a construction seeded by `seed`.
HPSF_FN CuckooParams CuckooFunctions(uint seed, uint level, uint attempt, uint size, uint functions) {
  RngCounter c;
  c.seed = seed;
  c.frame = level;
  c.pixel = attempt;
  c.sample_index = 0u;
  c.bounce = 0u;
  uint prefix = RngPrefix(c);
  CuckooParams p;
  p.size = size;
  p.functions = functions;
  p.a0 = 1u + RandomBitsFromPrefix(prefix, 0u) % (kCuckooPrime - 1u);
  p.b0 = RandomBitsFromPrefix(prefix, 1u) % kCuckooPrime;
  p.a1 = 1u + RandomBitsFromPrefix(prefix, 2u) % (kCuckooPrime - 1u);
  p.b1 = RandomBitsFromPrefix(prefix, 3u) % kCuckooPrime;
  p.a2 = 1u + RandomBitsFromPrefix(prefix, 4u) % (kCuckooPrime - 1u);
  p.b2 = RandomBitsFromPrefix(prefix, 5u) % kCuckooPrime;
  p.a3 = 1u + RandomBitsFromPrefix(prefix, 6u) % (kCuckooPrime - 1u);
  p.b3 = RandomBitsFromPrefix(prefix, 7u) % kCuckooPrime;
  return p;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_CUCKOO_H
