#include "core/hashed_run.h"

#include <array>
#include <optional>

namespace hpsf {

std::uint32_t LevelPlacement(const HashedRun& run, std::size_t i, std::uint32_t k) {
  if (k == 0) return run.placements[i];
  const std::size_t at = std::size_t(k - 1) * run.placements.size() + i;
  return at < run.coarser_placements.size() ? run.coarser_placements[at] : kNotPlaced;
}

shared::LevelChoice ResolvedSlot(const HashedRun& run, std::size_t i) {
  const std::uint32_t capacity = run.table.capacity;
  shared::LevelChoice choice = shared::NoLevelChosen();
  for (std::uint32_t k = 0; k < run.table.levels; ++k) {
    const std::uint32_t slot = LevelPlacement(run, i, k);
    const std::uint64_t count = slot < capacity ? run.table.counts[slot] : 0;
    choice = shared::ChooseLevel(choice, k, slot, count, capacity, run.min_count);
  }
  return choice;
}

void CountResolvedLevels(HashedRun& run) {
  run.resolved_at_level.assign(run.table.levels, 0);
  for (std::size_t i = 0; i < run.placements.size(); ++i) {
    const shared::LevelChoice chosen = ResolvedSlot(run, i);
    if (chosen.slot < run.table.capacity) ++run.resolved_at_level[chosen.level];
  }
}

std::vector<bool> AliasedSlots(const HashedRun& run) {
  std::vector<std::optional<std::array<std::uint32_t, 6>>> key_of(run.table.capacity);
  std::vector<bool> aliased(run.table.capacity, false);
  for (std::size_t i = 0; i < run.placements.size(); ++i) {
    const std::uint32_t slot = run.placements[i];
    if (slot >= run.table.capacity) continue;
    const shared::KeyWords& w = run.keys[i].words;
    const std::array<std::uint32_t, 6> key = {w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra};
    if (key_of[slot] && *key_of[slot] != key) aliased[slot] = true;
    key_of[slot] = key;
  }
  return aliased;
}

void CountProbes(HashedRun& run) {
  run.probe_failures = 0;
  run.probe_lengths.assign(run.table.probe_limit, 0);
  const shared::ProbeScheme scheme = ProbeSchemeOf(run.table);
  for (std::size_t i = 0; i < run.placements.size(); ++i) {
    const std::uint32_t slot = run.placements[i];
    if (slot == kProbeFailure) ++run.probe_failures;
    if (slot >= run.table.capacity) continue;
    // A placement outside its window is the checker's to name (kSlotOutsideWindow); it has no probe length.
    const std::uint32_t index = shared::ProbeIndex(scheme, run.keys[i].slot0, slot);
    if (index != shared::kNoCandidate) ++run.probe_lengths[index];
  }
}

void CountCoarserProbes(HashedRun& run, const KeyParams& params) {
  const std::size_t n = run.placements.size();
  const shared::ProbeScheme scheme = ProbeSchemeOf(run.table);
  for (std::size_t at = 0; at < run.coarser_placements.size(); ++at) {
    const std::uint32_t slot = run.coarser_placements[at];
    if (slot == kProbeFailure) ++run.probe_failures;
    if (slot >= run.table.capacity) continue;
    const KeyResult key = shared::KeyAtLevel(params, run.keys[at % n], std::uint32_t(at / n + 1));
    const std::uint32_t index = shared::ProbeIndex(scheme, key.slot0, slot);
    if (index != shared::kNoCandidate) ++run.probe_lengths[index];
  }
}

}  // namespace hpsf
