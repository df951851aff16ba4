#include "verifier/checker/classified_slots.h"

#include <algorithm>

#include "core/level_seed.h"
#include "core/level_touches.h"
#include "core/shared/level_seed.h"

namespace hpsf {

bool ClassifiedSlots::SeedTainted(const FullKey& key) const {
  const shared::KeyWords w{key[0], key[1], key[2], key[3], key[4], key[5]};
  auto tainted = [&](const shared::KeyWords& n) {
    return tainted_.contains({n.cell_x, n.cell_y, n.cell_z, n.level, n.normal, n.extra});
  };
  const shared::KeyWords parent = shared::ParentKeyWords(w);
  if (tainted(parent) || LookupAliased(parent)) return true;
  for (std::uint32_t child = 0; child < shared::kLevelSeedChildren; ++child) {
    const shared::KeyWords c = shared::ChildKeyWords(w, child);
    if (tainted(c) || LookupAliased(c)) return true;
  }
  return false;
}

bool ClassifiedSlots::LookupAliased(const shared::KeyWords& n) const {
  if (!previous_table_) return false;
  const std::optional<std::uint32_t> slot = FindSlotInTable(*previous_table_, n, normal_in_index_);
  if (!slot) return false;
  const FullKey wanted{n.cell_x, n.cell_y, n.cell_z, n.level, n.normal, n.extra};
  return previous_key_of_[*slot] != wanted;
}

const std::vector<bool>& ClassifiedSlots::AddFrame(const HashedRun& run, const std::vector<bool>& fed) {
  const std::size_t capacity = run.table.capacity;
  if (key_of_.size() != capacity) {
    key_of_.assign(capacity, std::nullopt);
    aliased_.assign(capacity, false);
    after_failure_.assign(capacity, false);
    if (evicts_under_pressure_) keys_here_.assign(capacity, {});
  }
  if (seeds_levels_) previous_key_of_ = key_of_;
  // Every level a record was added at is a touch of its own (core/level_touches.h).
  const LevelTouches touches(run.table, run.keys, run.placements, run.coarser_placements, normal_in_index_);
  auto key_of = [&](std::size_t i) {
    const shared::KeyWords& w = touches.keys()[i].words;
    return FullKey{w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra};
  };
  for (std::size_t i = 0; i < touches.size(); ++i) {
    const bool differs =
        touches.placements()[i] == kProbeFailure ||
        (touches.RecordOf(i) < fed.size() && fed[touches.RecordOf(i)] && touches.keys()[i].status == shared::kKeyed);
    if (differs) failed_.insert(key_of(i));
    if (differs && seeds_levels_) tainted_.insert(key_of(i));
  }
  for (std::size_t i = 0; i < touches.size(); ++i) {
    const std::uint32_t slot = touches.placements()[i];
    if (slot >= capacity) continue;
    const FullKey key = key_of(i);
    // New, seeded from taint: a taint itself for the cells seeded from it in later frames.
    if (seeds_levels_ && !key_of_[slot] && SeedTainted(key)) {
      after_failure_[slot] = true;
      tainted_.insert(key);
    }
    if (key_of_[slot] && *key_of_[slot] != key) {
      aliased_[slot] = true;
      if (seeds_levels_) tainted_.insert({key, *key_of_[slot]});
    }
    key_of_[slot] = key;
    if (evicts_under_pressure_ &&
        std::find(keys_here_[slot].begin(), keys_here_[slot].end(), key) == keys_here_[slot].end())
      keys_here_[slot].push_back(key);
    if (failed_.contains(key)) after_failure_[slot] = true;
  }
  classified_.assign(capacity, false);
  aliased_slots_ = 0;
  for (std::size_t s = 0; s < capacity; ++s) {
    classified_[s] = aliased_[s] || after_failure_[s];
    aliased_slots_ += aliased_[s];
  }
  classified_records_ = 0;
  for (const std::uint32_t slot : touches.placements()) classified_records_ += slot < capacity && classified_[slot];
  any_ = any_ || run.probe_failures > 0 || std::find(classified_.begin(), classified_.end(), true) != classified_.end();
  // A slot left empty or a tombstone (no count) starts afresh in the next frame.
  for (std::size_t s = 0; s < capacity; ++s) {
    if (run.table.counts[s] == 0) {
      if (evicts_under_pressure_) {  // evicted under pressure: its cells live on in the reference
        failed_.insert(keys_here_[s].begin(), keys_here_[s].end());
        if (seeds_levels_) tainted_.insert(keys_here_[s].begin(), keys_here_[s].end());
        keys_here_[s].clear();
      }
      key_of_[s].reset();
      aliased_[s] = after_failure_[s] = false;
    }
  }
  if (seeds_levels_) previous_table_ = run.table;
  return classified_;
}

}  // namespace hpsf
