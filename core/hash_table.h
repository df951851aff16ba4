// The GPU hash table's final state, as every hashed backend dumps it: one tag, three channel sums and a count
// per slot. The table checker judges a backend from this and the per-record placements alone.
#ifndef HPSF_CORE_HASH_TABLE_H
#define HPSF_CORE_HASH_TABLE_H

#include <array>
#include <cstdint>
#include <vector>

#include "core/filter_config.h"
#include "core/key_batch.h"
#include "core/shared/table_params.h"

namespace hpsf {

// A slot's tag: 0 marks an empty slot, anything else is a key's stored identity (core/key_identity.h): a reduced
// fingerprint of at most 32 bits, or a full key of 64. A named type so that a priority field (Binder et al.
// §3.4.3) could widen it further.
using SlotTag = std::uint64_t;
inline constexpr SlotTag kEmptyTag = 0;

// The identity a slot holding this key stores (core/shared/key.h).
inline SlotTag StoredIdentity(const KeyResult& key) { return (SlotTag(key.identity_high) << 32) | key.fingerprint; }

// Placement of a record: the slot it was added to, or one of these.
inline constexpr std::uint32_t kNotPlaced = shared::kPlacementNotPlaced;        // no vertex, unkeyable or rejected
inline constexpr std::uint32_t kProbeFailure = shared::kPlacementProbeFailure;  // probed its whole window in vain

struct HashTableDump {
  std::uint32_t capacity = 0;
  std::uint32_t probe_limit = 0;
  ProbeKind probing = ProbeKind::kLinear;
  std::uint32_t fingerprint_bits = 32;
  KeyIdentity key_identity = KeyIdentity::kFingerprint;  // kFull: every tag is a full key (64 bits)
  Accumulation accumulation = Accumulation::kFixed64;
  int fixed_point_bits = 0;
  std::uint32_t levels = 1;  // --levels: each record is added at its own cell and levels - 1 coarser ones
  std::vector<SlotTag> tags;
  std::vector<std::array<std::uint64_t, 3>> fixed_sums;  // fixed64, and packed-decimal's 32-bit words
  std::vector<std::array<float, 3>> float_sums;          // float32
  std::vector<std::uint64_t> counts;                     // packed-decimal: the count word's 24-bit count
  // --second-moments (core/shared/second_moment.h): per slot, the sum of its records' squared brightness, fixed64
  // at 2^G or float32. Empty otherwise.
  bool second_moments = false;
  int square_bits = 0;
  std::vector<std::uint64_t> fixed_squares;
  std::vector<float> float_squares;
  // packed-decimal (core/shared/packed_sums.h): the frame counter of each slot's count word. Empty otherwise.
  std::vector<std::uint32_t> frame_counters;
  // With eviction (core/eviction.h): the last frame a record was added to each slot. A slot whose tag is set
  // and whose count is 0 is a tombstone: an evicted cell that still holds its tag, so that a lookup probing past
  // it never stops at a hole (docs/design/defects.md, D7). Empty without eviction.
  std::vector<std::uint32_t> last_seen;
  // With --compaction occupied-list (core/compaction.h): the list of occupied slots as the device left it, in its
  // order. Every slot whose tag is set, once, and nothing else; the checker holds it to that.
  bool compacted = false;
  std::vector<std::uint32_t> occupied;
};

inline shared::ProbeScheme ProbeSchemeOf(const HashTableDump& table) {
  return MakeProbeScheme(table.probing, table.capacity, table.probe_limit);
}

}  // namespace hpsf

#endif  // HPSF_CORE_HASH_TABLE_H
