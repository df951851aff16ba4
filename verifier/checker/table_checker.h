// The table checker (docs/design/contract.md): judges a hashed backend from
// its final tags, sums and counts and each record's key and placement alone, without knowing the insertion
// order. Every violation names the invariant, the slot and the records involved.
// Over frames, it judges one frame from the table before it, the frame's records and placements and
// the table after: with temporal integration and no eviction, a claimed slot keeps its tag, and each slot's
// count and sums grow by exactly what the frame placed there. With eviction (core/eviction.h) the table after is
// the state after the eviction pass: a slot the frame touched is never evicted and its last-seen frame is this
// one; a live slot the policy evicts is a tombstone with zero count and sums (no evicted estimate comes back)
// and one it keeps is unchanged; a tombstone stays exactly when a live slot lies after it within the probe limit
// with no empty slot between, the rule that leaves no hole on any live slot's probe path (D7). With a blending
// temporal mode (core/temporal.h), a slot that held samples before the frame and that the frame added to holds
// the blend of the two: in fixed64 exactly core's BlendCellState of the table before and the frame's exact sums;
// in float32 its count exactly (ema; adaptive: between the frame's count and the capped history's plus it) and
// its average within the bounds of the history's and the frame's averages, widened by float32's rounding. With
// compaction (core/compaction.h), the table's occupied list holds every slot whose tag is set exactly once and no
// other slot, whatever its order. With --levels (core/shared/levels.h) each of a record's levels is judged as a record
// of its own (a touch: its key derived from the record's own, its placement, the record's contribution), and the
// levels nest: what a frame added to a coarser cell is what it added to its children by the records that reach it,
// plus the records whose own cell it is.
#ifndef HPSF_VERIFIER_CHECKER_TABLE_CHECKER_H
#define HPSF_VERIFIER_CHECKER_TABLE_CHECKER_H

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/eviction.h"
#include "core/hash_table.h"
#include "core/key_batch.h"
#include "core/level_seed.h"
#include "core/record.h"
#include "core/temporal.h"

namespace hpsf {

enum class TableInvariant {
  kPlacementOfUnkeyedRecord,    // a record without a key was placed, or a keyed one was neither placed nor failed
  kSlotOutsideWindow,           // a placed record's slot is not within probe_limit of its slot0
  kTagIsNotTheFingerprint,      // a placed record's slot holds another tag
  kEarlierSlotEmptyOrMatching,  // an earlier slot of the window is empty or holds the fingerprint
  kFailureWindowNotFull,        // a probe failure's window holds an empty slot or the fingerprint
  kCountMismatch,               // a slot's count differs from the records placed there
  kSumMismatch,                 // fixed64, packed-decimal: not the exact sum; float32: outside gamma(n-1) * sum|c|
  kEmptySlotNotZero,            // tag 0 with a count or sum
  kOrphanTag,                   // a non-zero tag that no placed record carries
  kTotalMismatch,               // the table total differs from the placed contributions
  kTagChangedAcrossFrames,      // a slot claimed before the frame holds another tag, or none, after it
  kEvictionPolicy,              // a slot the policy evicts still live, or one it keeps evicted
  kLastSeenWrong,               // a slot's last-seen frame is not this frame (touched) or its earlier one
  kHoleBeforeLiveSlot,          // a tombstone emptied though a live slot after it may have probed past it (D7)
  kTombstoneKept,               // a tombstone kept though no live slot after it can need it (the table fills)
  kTemporalBlend,               // a blended cell is not the blend of its history and the frame (core/temporal.h)
  kCellSplit,                   // a record claimed a slot though its cell lived in the window before the frame
  kOccupiedList,                // with compaction: the list misses an occupied slot, lists one twice, or an empty one
  kPackedSettle,                // packed-decimal: a slot is not the settle (halving, frame counter) of its exact sums
  kLevelNesting,                // --levels: a coarser cell's frame adds differ from those of its children that reach it
  kSquareSumMismatch,           // --second-moments: a slot's square sum is not its records' (as kSumMismatch's sums)
};
const char* ToString(TableInvariant invariant);

struct TableViolation {
  TableInvariant invariant;
  std::uint32_t slot = 0xFFFFFFFFu;
  std::vector<std::uint32_t> records;
  std::string detail;
  std::string ToString() const;
};

struct TableCheckInput {
  const HashTableDump& table;
  std::span<const Record> records;
  std::span<const KeyResult> keys;            // per record, from core
  std::span<const std::uint32_t> placements;  // per record
  // The table before this frame, of the same shape and F; null: the frame started from an empty table.
  const HashTableDump* before = nullptr;
  Eviction eviction = {};       // the sequence's policy; the tables then carry last_seen
  std::uint32_t frame = 0;      // this frame's number
  Temporal temporal = {};       // the sequence's temporal mode
  LevelSeed level_seed = {};    // the sequence's --level-change
  bool normal_in_index = true;  // the key's, for the neighbours' windows a seed is looked up in and coarser levels
  // With table.levels L > 1 (core/shared/levels.h), record i is also added k levels above its own cell, k = 1 .. L - 1,
  // placed at coarser_placements[(k - 1) n + i]. The checker derives those cells' keys from the records' own.
  std::span<const std::uint32_t> coarser_placements = {};
};

std::vector<TableViolation> CheckTable(const TableCheckInput& input);

// The occupied list alone (kOccupiedList): each slot whose tag is set listed once, nothing else. CheckTable holds a
// compacted table's list to it; the capture judge holds a team's list before the frame to the table before.
std::vector<TableViolation> CheckOccupiedListOf(const HashTableDump& table);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CHECKER_TABLE_CHECKER_H
