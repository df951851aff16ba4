// The HashCache's checker (Roth et al.'s cache, docs/design/hashcache.md): what a backend's update of the cache must
// hold, whatever schedule it ran under.
// - A frame: the backend's cache after the frame is the reference's update of the cache before it (same maps, same
//   fronts claimed earlier) by the frame's samples, given the backend's claims, bit for bit in every data array; and
//   each claim is the side of an element that reached the cell. Since the update has no other race, this holds for
//   float32 as for fixed64.
// - The sums (fixed64): each finest cell's side holds the exact sums and count of the samples in the cell on that
//   side of its front, and each coarser cell's side those of its children's sides on that side of its front (a
//   child's front standing for the child's front, its negation for the child's back), summed from the samples up,
//   so a wrong cell is named at its own level alone. Under the atomics rule every level's cells hold their samples
//   as the finest level's do.
#ifndef HPSF_CORE_HASHCACHE_CHECK_H
#define HPSF_CORE_HASHCACHE_CHECK_H

#include <span>
#include <string>
#include <vector>

#include "core/hashcache.h"

namespace hpsf {

// `after` must be `before` updated by `samples`; each problem names the level, the slot, the cell and the array.
std::vector<std::string> CheckHashCacheFrame(const HashCache& before, const HashCache& after,
                                             std::span<const HashCacheSample> samples);

// A fixed64 cache updated, from empty, by every sample in `samples` (all frames'): the sums and counts summed
// directly, sample by sample and child by child, with no sort and no reduce.
std::vector<std::string> CheckHashCacheSums(const HashCache& cache, std::span<const HashCacheSample> samples);

}  // namespace hpsf

#endif  // HPSF_CORE_HASHCACHE_CHECK_H
