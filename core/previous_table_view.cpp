#include "core/previous_table_view.h"

#include <array>
#include <memory>
#include <unordered_map>

#include "core/cell_moments.h"
#include "core/error.h"
#include "core/filter_result.h"
#include "core/fnv1a.h"
#include "core/hash_table.h"
#include "core/level_seed.h"
#include "core/neighbour_search.h"

namespace hpsf {
namespace {

struct KeyWordsHash {
  std::size_t operator()(const std::array<std::uint32_t, 6>& key) const { return Fnv1a(key.data(), sizeof key); }
};

}  // namespace

PreviousTableView::PreviousTableView(const FilterConfig& config, const KeyParams& key_params)
    : survival_(config.survival),
      path_graph_(config.path_graph),
      key_params_(key_params),
      accumulation_(config.accumulation) {}

PreviousTableView::PreviousTableView(const FilterConfig& config, const KeyParams& key_params,
                                     const FilterResult& previous)
    : PreviousTableView(config, key_params) {
  fixed_point_bits_ = previous.stats.fixed_point_bits;
  square_bits_ = previous.stats.square_bits;
  // Hashed, not ordered: the tracer looks every sample's primary vertex up.
  auto cells = std::make_shared<std::unordered_map<std::array<std::uint32_t, 6>, std::uint32_t, KeyWordsHash>>();
  cells->reserve(previous.cells.size());
  for (std::uint32_t c = 0; c < previous.cells.size(); ++c) cells->emplace(previous.cells[c].key, c);
  lookup_ = [cells, &previous](const shared::KeyWords& w) -> std::optional<CellState> {
    const auto it = cells->find({w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra});
    if (it == cells->end()) return std::nullopt;
    const TableCell& c = previous.cells[it->second];
    return CellState{c.fixed_sum, c.float_sum, c.count, c.fixed_square, c.float_square};
  };
}

PreviousTableView::PreviousTableView(const FilterConfig& config, const KeyParams& key_params,
                                     const HashTableDump& previous)
    : PreviousTableView(config, key_params) {
  accumulation_ = previous.accumulation;
  fixed_point_bits_ = previous.fixed_point_bits;
  square_bits_ = previous.square_bits;
  if (!previous.second_moments) {
    throw ConfigError(config.survival.enabled() ? "--survival" : "--path-graph",
                      "the table before the frame keeps no second moments (--second-moments on)");
  }
  lookup_ = [&previous,
             normal_in_index = config.normal_in_index](const shared::KeyWords& w) -> std::optional<CellState> {
    const std::optional<std::uint32_t> slot = FindSlotInTable(previous, w, normal_in_index);
    if (!slot) return std::nullopt;
    CellState state = StateOfSlot(previous, *slot);
    if (IntegerSums(previous.accumulation)) {
      state.fixed_square = previous.fixed_squares[*slot];
    } else {
      state.float_square = previous.float_squares[*slot];
    }
    return state;
  };
}

std::optional<CellEstimate> PreviousTableView::Cell(const Record& vertex) const {
  if (!lookup_) return std::nullopt;
  const KeyResult key = shared::ComputeKey(key_params_, vertex);
  if (key.status != shared::kKeyed) return std::nullopt;
  const std::optional<CellState> cell = lookup_(key.words);
  if (!cell || cell->count < 2) return std::nullopt;
  StencilTotal one;
  one.Add(cell->fixed_sum, cell->float_sum, cell->count);
  return CellEstimate{one.Average(accumulation_, fixed_point_bits_),
                      MomentsOf(accumulation_, cell->fixed_sum, cell->float_sum, cell->fixed_square, cell->float_square,
                                cell->count, fixed_point_bits_, square_bits_)};
}

double PreviousTableView::Probability(const Record& vertex) const {
  if (!survival_.enabled()) return 1.0;
  const std::optional<CellEstimate> cell = Cell(vertex);
  return cell ? SurvivalProbability(survival_, cell->moments.variance) : 1.0;
}

}  // namespace hpsf
