// The HashCache (Roth et al. §3.1): for each level of the octree, the cuckoo map of the level's occupied cells
// (core/cuckoo_map.h) and the data arrays its slots index: the cell's front (core/shared/hashcache_cell.h), the light
// of its front and of its back (sums and counts), and the frame it was last wiped. Roth keeps the two sides' light in
// six half floats and one count; hpsf keeps each side's sums as its own table keeps a slot's (fixed64 at 2^F, exact,
// or float32) and a count per side, so that each side's average is its sum over its own count.
#ifndef HPSF_CORE_HASHCACHE_H
#define HPSF_CORE_HASHCACHE_H

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/accumulation.h"
#include "core/cuckoo_map.h"
#include "core/shared/occupancy.h"

namespace hpsf {

// One sample to cache: a vertex on the scene's surface, its normal as a record stores it (core/octahedral.h: u in the
// low 16 bits, v in the high), and the light it carries (Roth's E_j: without the vertex's albedo; a denormal channel
// reads as zero on every backend, as on a device that flushes them).
struct HashCacheSample {
  glm::vec3 position{0.0f};
  std::uint32_t normal = 0;
  glm::vec3 light{0.0f};
  std::uint32_t unused = 0;  // std430's padding
};
static_assert(sizeof(HashCacheSample) == 32, "HashCacheSample must match the std430 layout");

// A level's data arrays, one entry (or a few) per slot of its map.
struct HashCacheData {
  std::vector<std::uint32_t> front;       // a front word, or shared::kFrontUnclaimed
  std::vector<std::uint64_t> fixed_sums;  // fixed64: six per slot, the front's rgb then the back's, at 2^F
  std::vector<float> float_sums;          // float32: the same six in float
  std::vector<std::uint64_t> counts;      // two per slot: the front's samples, the back's
  std::vector<std::uint32_t> wiped;       // the frame the cell was last emptied (its construction's, so far)
  bool operator==(const HashCacheData&) const = default;
};

struct HashCacheLevel {
  int level = 0;       // 0 the finest
  int cells_log2 = 0;  // the level's cells per axis, log 2
  CuckooMap map;
  HashCacheData data;
};

// How a frame's samples reach the levels (core/hashcache_update.h):
// - sort and reduce (Roth's): the finest level's cells take the samples, each coarser level its children's sides
//   (a child's front standing for its front, its front negated for its back), each cell side once per frame, every
//   add in one order: fixed64 and float32 both reproducible;
// - atomics: every sample adds to its cell at every level by atomic adds, on the side its own normal lies on there;
//   fixed64 only (float32 adds in the order the device happens to take them).
enum class HashCacheUpdateRule { kSortAndReduce, kAtomics };

struct HashCache {
  shared::OccupancyGrid grid{};
  Accumulation accumulation = Accumulation::kFixed64;  // fixed64 or float32
  int fixed_point_bits = 0;                            // F of fixed64's sums
  HashCacheUpdateRule update = HashCacheUpdateRule::kSortAndReduce;
  std::vector<HashCacheLevel> levels;  // the finest first, the root last
};

// A cache over `grid` with one map per level (maps[l] of level l's occupied cells, the finest first) and empty data:
// every front unclaimed, every sum and count zero, every cell wiped at `frame`. A std::logic_error for packed-decimal
// accumulation, float32 by atomics, or a map count other than the grid's levels.
HashCache EmptyHashCache(const shared::OccupancyGrid& grid, std::vector<CuckooMap> maps, Accumulation accumulation,
                         int fixed_point_bits, std::uint32_t frame = 0,
                         HashCacheUpdateRule update = HashCacheUpdateRule::kSortAndReduce);

}  // namespace hpsf

#endif  // HPSF_CORE_HASHCACHE_H
