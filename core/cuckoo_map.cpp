#include "core/cuckoo_map.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <unordered_map>

namespace hpsf {

std::optional<std::uint32_t> CuckooMap::Find(std::uint32_t key) const {
  for (std::uint32_t i = 0; i < params.functions; ++i) {
    const std::uint32_t slot = shared::CuckooSlot(params, i, key);
    if (slots[slot] == key) return slot;
  }
  return std::nullopt;
}

std::uint32_t CuckooMaxChain(std::size_t keys, const CuckooBuildOptions& options) {
  return options.max_chain ? options.max_chain
                           : 7u * std::uint32_t(std::bit_width(std::max<std::size_t>(keys, 1))) + 16u;
}

std::uint32_t CuckooSlots(std::size_t keys, double space) {
  return std::max<std::uint32_t>(std::uint32_t(std::ceil(space * double(keys))), 1u);
}

CuckooBuild BuildCuckooMap(std::span<const std::uint32_t> keys, const CuckooBuildOptions& options) {
  const std::uint32_t max_chain = CuckooMaxChain(keys.size(), options);
  CuckooBuild build;
  double space = options.space;
  for (build.attempts = 1; build.attempts <= options.max_attempts; ++build.attempts, space *= options.growth) {
    const std::uint32_t size = CuckooSlots(keys.size(), space);
    CuckooMap& map = build.map;
    map.params = shared::CuckooFunctions(options.seed, options.level, build.attempts, size, options.functions);
    map.slots.assign(size, shared::kCuckooEmpty);
    build.evictions = 0;
    build.longest_chain = 0;
    bool failed = false;
    for (const std::uint32_t first : keys) {
      std::uint32_t key = first;
      std::uint32_t slot = shared::CuckooSlot(map.params, 0, key);
      std::uint32_t chain = 0;
      for (;;) {
        std::swap(key, map.slots[slot]);  // the exchange: the key goes in, whatever was there comes out
        if (key == shared::kCuckooEmpty) break;
        if (++chain > max_chain) {
          failed = !options.drop_at_limit;  // the broken variant drops the key it holds
          break;
        }
        slot = shared::CuckooNextSlot(map.params, key, slot);
      }
      build.evictions += chain;
      build.longest_chain = std::max(build.longest_chain, chain);
      if (failed) break;
    }
    if (!failed) {
      build.built = true;
      return build;
    }
  }
  build.attempts = options.max_attempts;
  return build;
}

std::vector<std::uint32_t> OccupiedKeys(const OccupancyLevel& level) {
  std::vector<std::uint32_t> keys;
  const int cells_log2 = level.grid().resolution_log2 - level.level();
  level.ForEachOccupied([&](int x, int y, int z) { keys.push_back(shared::CuckooKey(x, y, z, cells_log2)); });
  return keys;
}

std::vector<std::string> CheckCuckooMap(const CuckooMap& map, std::span<const std::uint32_t> keys) {
  std::vector<std::string> problems;
  std::unordered_map<std::uint32_t, std::uint32_t> wanted;  // key -> times found in a slot
  for (const std::uint32_t key : keys) wanted.emplace(key, 0);
  for (std::uint32_t slot = 0; slot < map.slots.size(); ++slot) {
    const std::uint32_t key = map.slots[slot];
    if (key == shared::kCuckooEmpty) continue;
    const auto it = wanted.find(key);
    if (it == wanted.end()) {
      problems.push_back("slot " + std::to_string(slot) + " holds key " + std::to_string(key) +
                         ", which is not an occupied cell");
      continue;
    }
    bool candidate = false;
    for (std::uint32_t i = 0; i < map.params.functions; ++i)
      candidate |= shared::CuckooSlot(map.params, i, key) == slot;
    if (!candidate) {
      problems.push_back("slot " + std::to_string(slot) + " holds key " + std::to_string(key) +
                         ", which is not one of its candidate slots");
    }
    if (++it->second == 2) problems.push_back("key " + std::to_string(key) + " is held twice");
  }
  for (const auto& [key, found] : wanted) {
    if (found == 0) problems.push_back("key " + std::to_string(key) + " is in none of its candidate slots");
  }
  std::sort(problems.begin(), problems.end());
  return problems;
}

}  // namespace hpsf
