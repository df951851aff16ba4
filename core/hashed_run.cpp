#include "core/hashed_run.h"

#include <array>
#include <optional>

namespace hpsf {

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

}  // namespace hpsf
