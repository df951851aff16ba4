#include "core/hashed_run.h"

#include <array>
#include <optional>

#include "core/level_seed.h"
#include "core/prefetch.h"

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

NeighbourReads SearchInTable(const HashedRun& run, const Record& r, std::size_t i, const shared::LevelChoice& chosen,
                             std::array<shared::KeyWords, shared::kStencilCells - 1>* corner_words) {
  NeighbourReads reads;
  reads.record = std::uint32_t(i);
  reads.level = chosen.level;
  reads.cells.fill(kNotRead);
  const KeyParams& params = run.key_params;
  const auto words = StencilNeighbourWords(params, r, shared::JitteredKeyPosition(params, r), chosen.level);
  // The seven lookups are independent: their first candidates are asked for at once, so the misses overlap.
  for (const shared::KeyWords& w : words) {
    const std::uint32_t slot0 = shared::IndexHash(w, params.normal_in_index) & params.capacity_mask;
    PrefetchLine(&run.table.tags[slot0]);
    PrefetchLine(&run.table.counts[slot0]);
  }
  for (std::size_t c = 0; c < words.size(); ++c) {
    const std::optional<std::uint32_t> found = FindSlotInTable(run.table, words[c], params.normal_in_index != 0);
    if (found) reads.cells[c] = *found;
  }
  if (corner_words) *corner_words = words;
  return reads;
}

std::optional<glm::dvec3> ResolvedAverage(const HashedRun& run, const Record& r, std::size_t i,
                                          const shared::LevelChoice& chosen, NeighbourReads* reads,
                                          const SlotSearch* search) {
  const HashTableDump& table = run.table;
  if (chosen.slot >= table.capacity) return std::nullopt;
  const bool integer = IntegerSums(table.accumulation);
  StencilTotal total;
  const auto add = [&](std::uint32_t slot) {
    total.Add(integer ? table.fixed_sums[slot] : std::array<std::uint64_t, 3>{},
              integer ? std::array<float, 3>{} : table.float_sums[slot], table.counts[slot]);
  };
  add(chosen.slot);
  if (Searches(run.neighbour_search, chosen, table.capacity)) {
    const NeighbourReads searched = search ? (*search)(r, i, chosen) : SearchInTable(run, r, i, chosen);
    for (const std::uint32_t slot : searched.cells) {
      if (slot != kNotRead) add(slot);
    }
    if (reads) *reads = searched;
  }
  const glm::dvec3 average = total.Average(table.accumulation, table.fixed_point_bits);
  if (!run.interpolation.enabled()) return average;
  return Interpolated(run.interpolation, SlotWeight(run.interpolation, table, chosen.slot), average,
                      OwnLight(run.own_light, r, i));
}

void CountSearches(HashedRun& run, const RecordBatch& batch) {
  run.records_searched = run.neighbours_read = 0;
  if (!run.neighbour_search) return;
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    const shared::LevelChoice chosen = ResolvedSlot(run, i);
    if (!Searches(true, chosen, run.table.capacity)) continue;
    const NeighbourReads reads = SearchInTable(run, batch.records[i], i, chosen);
    ++run.records_searched;
    for (const std::uint32_t slot : reads.cells) run.neighbours_read += slot != kNotRead;
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
