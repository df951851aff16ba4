// A record's touches under --levels (core/shared/levels.h): touch k n + i adds record i at k levels above its own
// cell, its key derived from the record's own and its placement from the run's. With one level the touches are the
// records, and no array is copied. The checker, the contract's classes and its comparison with the reference walk
// touches as they walked records.
#ifndef HPSF_CORE_LEVEL_TOUCHES_H
#define HPSF_CORE_LEVEL_TOUCHES_H

#include <cstdint>
#include <span>
#include <vector>

#include "core/hash_table.h"
#include "core/key_batch.h"

namespace hpsf {

class LevelTouches {
 public:
  // keys and placements: per record, its own cell's; coarser: [(k - 1) n + i] for k = 1 .. table.levels - 1 (missing
  // entries, from a backend that wrote too few, read as never probed). The spans must outlive this object.
  LevelTouches(const HashTableDump& table, std::span<const KeyResult> keys, std::span<const std::uint32_t> placements,
               std::span<const std::uint32_t> coarser, bool normal_in_index);

  std::span<const KeyResult> keys() const { return keys_; }
  std::span<const std::uint32_t> placements() const { return placements_; }
  std::size_t size() const { return keys_.size(); }
  std::uint32_t RecordOf(std::size_t touch) const { return std::uint32_t(touch % records_); }
  std::uint32_t LevelOf(std::size_t touch) const { return std::uint32_t(touch / records_); }

 private:
  std::size_t records_;
  std::vector<KeyResult> derived_keys_;
  std::vector<std::uint32_t> all_placements_;
  std::span<const KeyResult> keys_;
  std::span<const std::uint32_t> placements_;
};

}  // namespace hpsf

#endif  // HPSF_CORE_LEVEL_TOUCHES_H
