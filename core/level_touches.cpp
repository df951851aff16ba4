#include "core/level_touches.h"

#include <algorithm>

#include "core/shared/levels.h"

namespace hpsf {

LevelTouches::LevelTouches(const HashTableDump& table, std::span<const KeyResult> keys,
                           std::span<const std::uint32_t> placements, std::span<const std::uint32_t> coarser,
                           bool normal_in_index)
    : records_(std::max<std::size_t>(keys.size(), 1)), keys_(keys), placements_(placements) {
  if (table.levels <= 1) return;
  // KeyAtLevel reads these four of the key parameters.
  shared::KeyParams params{};
  params.capacity_mask = table.capacity - 1u;
  params.fingerprint_bits = table.fingerprint_bits;
  params.normal_in_index = normal_in_index ? 1u : 0u;
  params.key_identity = table.key_identity == KeyIdentity::kFull ? shared::kIdentityFull : shared::kIdentityFingerprint;
  derived_keys_.assign(keys.begin(), keys.end());
  for (std::uint32_t k = 1; k < table.levels; ++k) {
    for (const KeyResult& own : keys) derived_keys_.push_back(shared::KeyAtLevel(params, own, k));
  }
  all_placements_.assign(placements.begin(), placements.end());
  all_placements_.insert(all_placements_.end(), coarser.begin(), coarser.end());
  all_placements_.resize(derived_keys_.size(), kNotPlaced);
  keys_ = derived_keys_;
  placements_ = all_placements_;
}

}  // namespace hpsf
