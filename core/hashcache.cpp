#include "core/hashcache.h"

#include <stdexcept>
#include <utility>

#include "core/shared/hashcache_cell.h"

namespace hpsf {

HashCache EmptyHashCache(const shared::OccupancyGrid& grid, std::vector<CuckooMap> maps, Accumulation accumulation,
                         int fixed_point_bits, std::uint32_t frame, HashCacheUpdateRule update) {
  if (accumulation == Accumulation::kPackedDecimal) throw std::logic_error("the HashCache has no packed-decimal sums");
  if (update == HashCacheUpdateRule::kAtomics && accumulation != Accumulation::kFixed64) {
    throw std::logic_error("the HashCache's atomics update sums fixed64 only");
  }
  if (maps.size() != std::size_t(grid.resolution_log2) + 1) throw std::logic_error("a HashCache needs a map a level");
  HashCache cache;
  cache.grid = grid;
  cache.accumulation = accumulation;
  cache.fixed_point_bits = fixed_point_bits;
  cache.update = update;
  for (std::size_t l = 0; l < maps.size(); ++l) {
    HashCacheLevel level;
    level.level = int(l);
    level.cells_log2 = grid.resolution_log2 - int(l);
    level.map = std::move(maps[l]);
    const std::size_t slots = level.map.slots.size();
    level.data.front.assign(slots, shared::kFrontUnclaimed);
    if (accumulation == Accumulation::kFixed64) {
      level.data.fixed_sums.assign(6 * slots, 0);
    } else {
      level.data.float_sums.assign(6 * slots, 0.0f);
    }
    level.data.counts.assign(2 * slots, 0);
    level.data.wiped.assign(slots, frame);
    cache.levels.push_back(std::move(level));
  }
  return cache;
}

}  // namespace hpsf
