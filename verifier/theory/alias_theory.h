// Fingerprint aliases (Binder et al. §3.2.1): a key whose b-bit fingerprint equals the tag of another key in its
// probe window joins that key's slot. Given the table a new key meets, the chance is exact: the sum, over the
// distinct tags it would compare before reaching an empty slot, of the probability that its fingerprint is that
// tag. The statistics tests and `hpsf stats` insert distinct keys one by one and hold the aliases counted to
// the sum of those chances.
#ifndef HPSF_VERIFIER_THEORY_ALIAS_THEORY_H
#define HPSF_VERIFIER_THEORY_ALIAS_THEORY_H

#include <cstdint>
#include <span>

#include "core/key_batch.h"
#include "core/probing.h"

namespace hpsf {

// The probability that a uniform 32-bit hash, reduced to `bits` bits as the key path does (top bits, 0 made 1),
// equals `tag`: 2^-b, and twice that for tag 1, which also takes the hashes that reduce to 0.
double FingerprintProbability(std::uint32_t tag, std::uint32_t bits);

struct AliasTally {
  std::uint64_t keys = 0;     // distinct keys inserted
  std::uint64_t aliased = 0;  // keys that joined another key's slot
  std::uint64_t failed = 0;   // keys that found their window full of other tags
  double predicted = 0.0;     // sum over keys of the chance of an alias, given the table each one met
  double variance = 0.0;      // sum over keys of p (1 - p)
  double compared = 0.0;      // other keys' tags compared, summed over keys (what the chance grows with)
  double Rate() const { return keys == 0 ? 0.0 : double(aliased) / double(keys); }
  double PredictedRate() const { return keys == 0 ? 0.0 : predicted / double(keys); }
};

// Inserts `keys` (distinct full keys, in this order; their slot0 and fingerprint from the key path, unkeyed
// results skipped) one at a time into a table of `capacity` slots (a power of two), each trying the probe_limit
// candidates its scheme gives (core/shared/probe_scheme.h; bounded linear probing by default).
AliasTally InsertAndCountAliases(std::span<const KeyResult> keys, std::uint32_t capacity, std::uint32_t probe_limit,
                                 std::uint32_t fingerprint_bits, ProbeKind probing = ProbeKind::kLinear);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_THEORY_ALIAS_THEORY_H
