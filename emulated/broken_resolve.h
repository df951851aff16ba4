// Broken variants of the resolve's fallbacks for few-vertex cells (core/shared/levels.h,
// core/shared/neighbour_search.h; docs/design/defects.md, "Broken levels"), for the emulator's resolve, as
// resolve_*.spv variants are for Vulkan's: each a way a team's resolve goes wrong, which the gate must catch.
#ifndef HPSF_EMULATED_BROKEN_RESOLVE_H
#define HPSF_EMULATED_BROKEN_RESOLVE_H

#include "core/hashed_run.h"

namespace hpsf {

enum class ResolveDefect {
  kNone,
  kLevelWrongCount,   // every level judged by the count of the record's own cell (resolve_LEVEL_WRONG_COUNT.spv)
  kClaims,            // a corner's lookup claims the first empty slot of its window, as an insertion would
  kStopsAtTombstone,  // a lookup ends at an eviction's tombstone as at an empty slot: a cell probed past it is missed
  kStencilTruncated,  // the side of the cell's centre from q - trunc(q): at negative coordinates the wrong neighbour
};

// The level record i's resolve reads, with that defect (ResolvedSlot's choice where the defect is not a level's).
shared::LevelChoice BrokenLevelChoice(ResolveDefect defect, const HashedRun& run, std::size_t i);

// The search with that defect over the run's table, which kClaims writes (so the caller runs it on one thread).
SlotSearch BrokenSearch(ResolveDefect defect, HashedRun& run);

}  // namespace hpsf

#endif  // HPSF_EMULATED_BROKEN_RESOLVE_H
