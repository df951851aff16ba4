// A frame's update of the HashCache by sort and reduce (Roth et al. §3.2), the reference's. Level by level from the
// finest:
// 1. locate and claim: each element (at the finest level a sample, above it a finer level's segment) finds its cell's
//    slot in the level's map, claims the cell's front with its own side if no element has, and takes the side it lies
//    on (core/shared/hashcache_cell.h);
// 2. sort the elements by their order word: the segment word (cell << 1 | back) above, the element's origin below
//    (its sample's index, or the finer segment's word), so the order depends on no slot and no schedule;
// 3. reduce each segment, its elements added one after another in that order, and update its cell's side once;
// 4. each segment becomes an element of the level above: its parent's key, its side (the cell's front, or the front
//    negated for the back), its word as origin, its sums and count.
// No atomic adds: fixed64's sums are exact, and float32's are the same bits on every backend and thread count, since
// every add happens in one order. Only the front's claim races (which element claims first); given the claims, every
// bit is determined.
//
// A cache whose rule is atomics (core/hashcache.h) is updated level by level too, each sample locating its cell at the
// level, claiming its front with its own normal and adding its light to the side its normal lies on.
#ifndef HPSF_CORE_HASHCACHE_UPDATE_H
#define HPSF_CORE_HASHCACHE_UPDATE_H

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/hashcache.h"

namespace hpsf {

struct HashCacheUpdateReport {
  std::uint64_t missed = 0;             // samples off the grid or in a cell no triangle occupies
  std::vector<std::uint64_t> segments;  // per level: the cell sides updated (atomics: the samples added)
  // With claims given: each claim no element that reached the cell made, each cell reached but left unclaimed, and
  // each parent of a reached cell missing from its level's map.
  std::vector<std::string> problems;
};

// The update of `cache` by `samples`. Where `claims` is given (per level, per slot: the fronts a backend's update
// left), a cell unclaimed before the frame is claimed with the claim given, and the report names each claim that is no
// side of an element that reached the cell; otherwise the first element in the level's element order claims.
HashCacheUpdateReport UpdateHashCache(HashCache& cache, std::span<const HashCacheSample> samples,
                                      const std::vector<std::vector<std::uint32_t>>* claims = nullptr);

}  // namespace hpsf

#endif  // HPSF_CORE_HASHCACHE_UPDATE_H
