// Multi-level accumulation (Binder et al. §3.3.2), written once for C++ and GLSL: a record is added to its own cell
// and to the cells that hold it at the levels-1 coarser levels. A coarser cell is its finer cell's key words shifted
// (core/shared/level_seed.h's ParentKeyWords, k times): x >> k for the same jittered point, so cells nest exactly, a
// cell at level l + k being the union of its 8^k descendants at level l (floor(q) >> k = floor(q 2^-k) for the
// power-of-two scales involved). Under level of detail it is also the very cell a record whose own level is l + k
// keys, so the levels of one table share their cells. The resolve reads, per record, the finest placed level whose
// count reaches min_count, else the coarsest placed one (docs/design/algorithm.md#multi-level-accumulation).
#ifndef HPSF_CORE_SHARED_LEVELS_H
#define HPSF_CORE_SHARED_LEVELS_H

#include "full_key.h"
#include "key.h"
#include "level_seed.h"
#include "table_params.h"

HPSF_SHARED_BEGIN

const uint kMaxLevels = 8u;  // --levels: 1 (a record's own cell only) .. 8

// The key of the cell k levels above a record's own, computed from its own key (the key path runs once). A full key
// always fits: the cell words only shrink, and the level word stays below 254 + kMaxLevels < 512.
HPSF_FN KeyResult KeyAtLevel(KeyParams p, KeyResult own, uint k) {
  if (k == 0u || own.status != kKeyed) return own;
  KeyResult c = own;
  c.words = CoarserKeyWords(own.words, k);
  c.level = own.level + int(k);
  StoredIdentity identity = IdentityOfWords(c.words, p.key_identity, p.fingerprint_bits);
  c.slot0 = Slot0AtLevel(own.words, k, p.normal_in_index, p.capacity_mask);
  c.fingerprint = identity.words.x;
  c.identity_high = identity.words.y;
  return c;
}

// Where a record's level k placement is kept: level-major, so level 0 is the single-level layout.
HPSF_FN uint LevelPlacementIndex(uint record, uint k, uint record_count) { return k * record_count + record; }

// The resolve's choice, folded over a record's levels from the finest: slot >= capacity where none is placed.
struct LevelChoice {
  uint slot;
  uint level;
  uint settled;  // 1 once a placed level's count reached min_count: coarser levels are not read
};

HPSF_FN LevelChoice NoLevelChosen() {
  LevelChoice c;
  c.slot = kPlacementNotPlaced;
  c.level = 0u;
  c.settled = 0u;
  return c;
}

// count: the slot's count as the resolve reads it (after the frame's blend, settle and eviction).
HPSF_FN LevelChoice ChooseLevel(LevelChoice c, uint k, uint slot, uint64_t count, uint capacity, uint min_count) {
  if (c.settled != 0u || slot >= capacity) return c;
  c.slot = slot;
  c.level = k;
  c.settled = count >= uint64_t(min_count) ? 1u : 0u;
  return c;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_LEVELS_H
