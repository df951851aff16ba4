#include "verifier/contract/search_check.h"

#include <array>

namespace hpsf {
namespace {

using FullKey = ClassifiedSlots::FullKey;

FullKey KeyOfWords(const shared::KeyWords& w) { return {w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra}; }

}  // namespace

SearchComparison CompareSearches(const RecordBatch& batch, const FilterResult& reference, const HashedRun& run,
                                 const ClassifiedSlots& classes, const std::vector<bool>& classified,
                                 const std::string& prefix, LevelVerdict& ideal) {
  SearchComparison result;
  if (!run.neighbour_search) return result;
  const std::uint32_t capacity = run.table.capacity;
  std::vector<std::size_t> reference_search(batch.records.size(), reference.neighbour_reads.size());
  for (std::size_t at = 0; at < reference.neighbour_reads.size(); ++at) {
    reference_search[reference.neighbour_reads[at].record] = at;
  }
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    const shared::LevelChoice chosen = ResolvedSlot(run, i);
    const bool searched = Searches(true, chosen, capacity);
    const bool reference_searched = reference_search[i] < reference.neighbour_reads.size();
    if (!searched && !reference_searched) continue;
    bool tainted = false;
    for (std::uint32_t k = 0; k < run.table.levels; ++k) {
      const std::uint32_t slot = LevelPlacement(run, i, k);
      tainted = tainted || slot == kProbeFailure || (slot < capacity && classified[slot]);
    }
    const std::string record = prefix + "record " + std::to_string(i);
    if (tainted) {
      ++result.classified;
      continue;
    }
    if (searched != reference_searched) {
      ideal.Fail(record + (searched ? " searched its neighbours, the reference's did not"
                                    : " did not search its neighbours, the reference's did"));
      continue;
    }
    const NeighbourReads& expected = reference.neighbour_reads[reference_search[i]];
    if (chosen.level != expected.level) {
      ideal.Fail(record + " searched " + std::to_string(chosen.level) + " levels up, the reference " +
                 std::to_string(expected.level));
      continue;
    }
    std::array<shared::KeyWords, shared::kStencilCells - 1> wanted;
    const NeighbourReads read = SearchInTable(run, batch.records[i], i, chosen, &wanted);
    bool failed = false;
    for (std::size_t c = 0; c < read.cells.size() && !failed; ++c) {
      const FullKey want = KeyOfWords(wanted[c]);
      const std::uint32_t slot = read.cells[c];
      const std::uint32_t cell = expected.cells[c];
      const std::string corner = record + " corner " + std::to_string(c + 1);
      if (slot != kNotRead && classified[slot]) {
        tainted = true;
      } else if (slot != kNotRead && classes.KeyOf(slot) != want) {
        tainted = true;  // the lookup aliased
      } else if (slot != kNotRead && cell == kNotRead) {
        ideal.Fail(corner + ": read slot " + std::to_string(slot) + ", a cell the reference's search did not find");
        failed = true;
      } else if (slot == kNotRead && cell != kNotRead) {
        if (classes.Lost(want)) {
          tainted = true;
        } else {
          ideal.Fail(corner + ": found no slot for a cell the reference's search read");
          failed = true;
        }
      }
    }
    if (failed) continue;
    if (tainted) {
      ++result.classified;
    } else {
      ++result.compared;
    }
  }
  return result;
}

}  // namespace hpsf
