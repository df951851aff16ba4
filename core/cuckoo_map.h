// One level's hash map of the HashCache (Roth et al. §3.1; the hashing is core/shared/cuckoo.h): its construction
// from the level's occupied cells with Roth's retry rule, its lookups, and the checker's invariants over it. This is
// the reference's construction: the keys inserted one after another, each by Alcantara et al.'s eviction chain.
#ifndef HPSF_CORE_CUCKOO_MAP_H
#define HPSF_CORE_CUCKOO_MAP_H

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/occupancy.h"
#include "core/shared/cuckoo.h"

namespace hpsf {

struct CuckooMap {
  shared::CuckooParams params{};
  std::vector<std::uint32_t> slots;  // a key, or shared::kCuckooEmpty

  // The slot that holds `key` among its candidates, if one does.
  std::optional<std::uint32_t> Find(std::uint32_t key) const;
};

struct CuckooBuildOptions {
  std::uint32_t functions = 4;      // candidate slots per key, 2 to 4
  std::uint32_t seed = 1;           // of the hash constants
  std::uint32_t level = 0;          // the level whose constants they are
  double space = 1.1;               // Roth's f_0: slots = ceil(f keys)
  double growth = 1.01;             // and f_n = f_{n-1} growth after a failed attempt
  std::uint32_t max_chain = 0;      // evictions before an insert fails; 0: 7 log2(keys) + 16
  std::uint32_t max_attempts = 64;  // a construction that fails so many times reports it
  // The broken variant: an insert that reaches the chain's limit drops the key it holds and reports nothing.
  bool drop_at_limit = false;
};

struct CuckooBuild {
  CuckooMap map;
  bool built = false;               // every key placed
  std::uint32_t attempts = 0;       // including the one that succeeded
  std::uint64_t evictions = 0;      // over the successful attempt's inserts
  std::uint32_t longest_chain = 0;  // evictions of the successful attempt's longest insert
};

// The evictions an insert may make before it fails: options.max_chain, or 7 log2(keys) + 16 where that is 0.
std::uint32_t CuckooMaxChain(std::size_t keys, const CuckooBuildOptions& options);
// The slots of an attempt at `space` slots a key: ceil(space keys), at least 1.
std::uint32_t CuckooSlots(std::size_t keys, double space);

// The keys must be distinct and below kCuckooEmpty.
CuckooBuild BuildCuckooMap(std::span<const std::uint32_t> keys, const CuckooBuildOptions& options);

// The occupied cells of a level as keys (shared::CuckooKey), in the field's order.
std::vector<std::uint32_t> OccupiedKeys(const OccupancyLevel& level);

// The map's invariants over the keys it must hold: every key in exactly one of its candidate slots, and no slot
// holding a key twice or a key that is not one of them (so a lookup of a cell that is not occupied fails: no slot
// holds it). Each problem names the key or the slot; none for a map that holds.
std::vector<std::string> CheckCuckooMap(const CuckooMap& map, std::span<const std::uint32_t> keys);

}  // namespace hpsf

#endif  // HPSF_CORE_CUCKOO_MAP_H
