// Broken variants of the resolve's neighbourhood search (core/shared/neighbour_search.h; docs/design/defects.md,
// "Broken levels"), for the emulator's resolve, as resolve_*.spv variants are for Vulkan's: each a way a lookup of a
// team's goes wrong, which the gate must catch.
#ifndef HPSF_EMULATED_BROKEN_SEARCH_H
#define HPSF_EMULATED_BROKEN_SEARCH_H

#include "core/hashed_run.h"

namespace hpsf {

enum class SearchDefect {
  kNone,
  kClaims,            // a corner's lookup claims the first empty slot of its window, as an insertion would
  kStopsAtTombstone,  // a lookup ends at an eviction's tombstone as at an empty slot: a cell probed past it is missed
  kStencilTruncated,  // the side of the cell's centre from q - trunc(q): at negative coordinates the wrong neighbour
};

// The search with that defect over the run's table, which kClaims writes (so the caller runs it on one thread).
SlotSearch BrokenSearch(SearchDefect defect, HashedRun& run);

}  // namespace hpsf

#endif  // HPSF_EMULATED_BROKEN_SEARCH_H
