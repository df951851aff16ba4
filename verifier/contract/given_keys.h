// Judging keys hpsf did not compute: a capture's (verifier/contract/capture_judgement.h) or a team's shader that writes
// its own (`--key-source shader`). The key words are opaque; the cells are the records of equal words.
//   level 1  what can be judged without hpsf's key: every keyed record's home slot inside the table, its identity
//            neither 0 (the empty marker) nor wider than the declared fingerprint nor priority eviction's tombstone
//            marker, and records of equal key words given equal home slots and identities (a key that is a function
//            of its cell)
//   level 3  the exact map over the key words: each cell's records in one slot or all failed, and outside the
//            classified slots each record's slot holds the frame's exact count of its cell, and in fixed64 its exact
//            sums (a slot with a history compared by what the frame added when the table integrates; under a
//            blending mode only slots new in the frame, the blend being level 2's)
#ifndef HPSF_VERIFIER_CONTRACT_GIVEN_KEYS_H
#define HPSF_VERIFIER_CONTRACT_GIVEN_KEYS_H

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/hashed_run.h"
#include "core/record.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf {

// Level 1 over `keys` (one per record); failures start with `prefix`. Returns how many keyed records were judged.
std::uint64_t JudgeGivenKeys(std::span<const KeyResult> keys, std::span<const Record> records, std::uint32_t capacity,
                             const FilterConfig& config, const std::string& prefix, LevelVerdict& verdict);

// Level 3 for one frame of `run` (its keys, placements and table; `before` the table before it, or null), outside the
// `classified` slots. Returns how many records were compared.
std::uint64_t CompareWithExactMap(std::span<const Record> records, const HashedRun& run, const HashTableDump* before,
                                  const std::vector<bool>& classified, const FilterConfig& config,
                                  const std::string& prefix, LevelVerdict& verdict);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_GIVEN_KEYS_H
