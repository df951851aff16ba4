#include "emulated/broken_resolve.h"

#include <cmath>

#include "core/shared/eviction_priority.h"
#include "core/shared/full_key.h"
#include "core/shared/probe_scheme.h"

namespace hpsf {
namespace {

// A lookup as core/level_seed.h's FindSlotInTable, with the defect's step.
std::optional<std::uint32_t> BrokenLookup(ResolveDefect defect, HashTableDump& table, const shared::KeyWords& words,
                                          bool normal_in_index) {
  const std::uint32_t slot0 = shared::IndexHash(words, normal_in_index ? 1u : 0u) & (table.capacity - 1u);
  const shared::StoredIdentity identity = shared::IdentityOfWords(
      words, table.key_identity == KeyIdentity::kFull ? shared::kIdentityFull : shared::kIdentityFingerprint,
      table.fingerprint_bits);
  if (!identity.fits) return std::nullopt;
  const SlotTag tag = shared::IdentityValue(identity.words);
  const shared::ProbeScheme scheme = ProbeSchemeOf(table);
  for (std::uint32_t probe = 0; probe < table.probe_limit; ++probe) {
    const std::uint32_t s = shared::CandidateSlot(scheme, slot0, probe);
    if (defect == ResolveDefect::kClaims && table.tags[s] == kEmptyTag) {
      table.tags[s] = tag;  // claimed, with no sample: the lookup found nothing, and left a tag no record carries
      return std::nullopt;
    }
    if (defect == ResolveDefect::kStopsAtTombstone && table.tags[s] == shared::kTombstoneTag) return std::nullopt;
    const std::uint32_t step = shared::LookupStep(table.tags[s], tag, table.counts[s]);
    if (step == shared::kLookupEnd) return std::nullopt;
    if (step == shared::kLookupFound) return s;
  }
  return std::nullopt;
}

}  // namespace

shared::LevelChoice BrokenLevelChoice(ResolveDefect defect, const HashedRun& run, std::size_t i) {
  if (defect != ResolveDefect::kLevelWrongCount) return ResolvedSlot(run, i);
  const std::uint32_t capacity = run.table.capacity;
  const std::uint32_t own = run.placements[i];
  const std::uint64_t own_count = own < capacity ? run.table.counts[own] : 0;  // the count every level is judged by
  shared::LevelChoice choice = shared::NoLevelChosen();
  for (std::uint32_t k = 0; k < run.table.levels; ++k) {
    choice = shared::ChooseLevel(choice, k, LevelPlacement(run, i, k), own_count, capacity, run.min_count);
  }
  return choice;
}

SlotSearch BrokenSearch(ResolveDefect defect, HashedRun& run) {
  return [defect, &run](const Record& r, std::size_t i, const shared::LevelChoice& chosen) {
    const KeyParams& params = run.key_params;
    const CellFinder find = [&](const shared::KeyWords& w) {
      return BrokenLookup(defect, run.table, w, params.normal_in_index != 0);
    };
    if (defect != ResolveDefect::kStencilTruncated || chosen.level != 0) {
      return SearchNeighbours(params, r, chosen, std::uint32_t(i), find);
    }
    NeighbourReads reads;
    reads.record = std::uint32_t(i);
    reads.cells.fill(kNotRead);
    const shared::KeyPosition at = shared::JitteredKeyPosition(params, r);
    const KeyResult own = shared::KeyAtPosition(params, r, at);
    const glm::vec3 q = shared::CellCoordinates(at.jittered, at.inverse_size);
    const glm::vec3 fraction = q - glm::trunc(q);  // negative below zero: the lower side, wrongly, half the time
    const glm::uvec3 sides(fraction.x >= 0.5f, fraction.y >= 0.5f, fraction.z >= 0.5f);
    for (std::uint32_t corner = 1; corner < shared::kStencilCells; ++corner) {
      const std::optional<std::uint32_t> found = find(shared::StencilCellWords(own.words, sides, corner));
      if (found) reads.cells[corner - 1] = *found;
    }
    return reads;
  };
}

}  // namespace hpsf
