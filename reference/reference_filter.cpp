#include "reference/reference_filter.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "core/footprint.h"
#include "core/input_check.h"
#include "core/key_batch.h"
#include "core/level_seed.h"
#include "core/neighbour_search.h"
#include "core/resolve.h"
#include "core/shared/fixed_point.h"
#include "core/shared/levels.h"
#include "core/shared/packed_sums.h"
#include "core/shared/second_moment.h"
#include "core/temporal.h"
#include "core/transport.h"

namespace hpsf {
namespace {

// The exact map forgets evicted cells outright: no tombstones, which only a hashed table needs. The frame's
// records keep their cells, which no policy evicts, renumbered.
void EvictCells(const FilterConfig& config, FilterResult& result) {
  std::vector<std::uint32_t> renumbered(result.cells.size(), kNoCell);
  std::vector<TableCell> kept;
  for (std::size_t c = 0; c < result.cells.size(); ++c) {
    if (config.eviction.Evicts(config.frame, result.cells[c].last_seen)) continue;
    renumbered[c] = static_cast<std::uint32_t>(kept.size());
    kept.push_back(result.cells[c]);
  }
  result.stats.cells_evicted = result.cells.size() - kept.size();
  result.cells = std::move(kept);
  for (std::vector<std::uint32_t>* placements : {&result.placement, &result.coarser_placement}) {
    for (std::uint32_t& cell : *placements) {
      if (cell != kNoCell) cell = renumbered[cell];
    }
  }
}

// The temporal blend (core/temporal.h) of each cell the frame added to that held samples before it.
void BlendCells(const FilterConfig& config, const std::vector<TableCell>& before, FilterResult& result) {
  const shared::TemporalParams params =
      MakeTemporalParams(config.temporal, config.accumulation, result.stats.fixed_point_bits, result.stats.square_bits);
  for (std::size_t c = 0; c < before.size(); ++c) {
    const TableCell& old = before[c];
    TableCell& cell = result.cells[c];
    if (old.count == 0 || cell.count == old.count) continue;
    const CellState blended = BlendCellState(
        params, config.accumulation, {old.fixed_sum, old.float_sum, old.count, old.fixed_square, old.float_square},
        {cell.fixed_sum, cell.float_sum, cell.count, cell.fixed_square, cell.float_square});
    cell.fixed_sum = blended.fixed_sum;
    cell.float_sum = blended.float_sum;
    cell.count = blended.count;
    cell.fixed_square = blended.fixed_square;
    cell.float_square = blended.float_square;
  }
}

// Resolution changes (core/level_seed.h): each cell new in this frame takes its seed from the cells before it, looked
// up by exact key. Its sums and count add to the frame's, so the float32 seed comes last in its sum.
void SeedNewCells(const FilterConfig& config, const FilterResult* previous,
                  const std::map<std::array<std::uint32_t, 6>, std::uint32_t>& cell_of_key, FilterResult& result) {
  const std::size_t old_cells = previous ? previous->cells.size() : 0;
  const bool fixed = IntegerSums(config.accumulation);
  const bool packed = config.accumulation == Accumulation::kPackedDecimal;
  const CellLookup lookup = [&](const shared::KeyWords& w) -> std::optional<CellState> {
    const auto it = cell_of_key.find({w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra});
    if (it == cell_of_key.end() || it->second >= old_cells) return std::nullopt;
    const TableCell& c = previous->cells[it->second];
    if (c.count == 0) return std::nullopt;
    return CellState{c.fixed_sum, c.float_sum, c.count};
  };
  for (std::size_t c = old_cells; c < result.cells.size(); ++c) {
    TableCell& cell = result.cells[c];
    const shared::KeyWords words{cell.key[0], cell.key[1], cell.key[2], cell.key[3], cell.key[4], cell.key[5]};
    const CellState seed = SeedOf(words, config.level_seed, fixed, lookup);
    if (seed.count == 0) continue;
    ++result.stats.cells_seeded;
    for (int k = 0; k < 3; ++k) {
      cell.fixed_sum[k] += seed.fixed_sum[k];
      cell.float_sum[k] += seed.float_sum[k];
      if (packed) cell.fixed_sum[k] &= 0xFFFFFFFFu;  // 32-bit words, as the device's
    }
    if (packed) {  // the count bits carry into the frame counter, as the device's add to the count word
      const std::uint32_t word =
          shared::PackCountWord(std::uint32_t(cell.count), cell.frames) + std::uint32_t(seed.count);
      cell.count = shared::PackedCount(word);
      cell.frames = shared::PackedFrames(word);
    } else {
      cell.count += seed.count;
    }
  }
}

// packed-decimal's settle (core/shared/packed_sums.h) of every cell, after the frame's adds.
void SettleCells(FilterResult& result) {
  for (TableCell& cell : result.cells) {
    const glm::uvec4 before(cell.fixed_sum[0], cell.fixed_sum[1], cell.fixed_sum[2],
                            shared::PackCountWord(std::uint32_t(cell.count), cell.frames));
    result.stats.cells_halved += cell.count > 0 && shared::PackedNeedsHalving(before);
    const glm::uvec4 after = shared::SettlePacked(before);
    cell.fixed_sum = {after.x, after.y, after.z};
    cell.count = shared::PackedCount(after.w);
    cell.frames = shared::PackedFrames(after.w);
  }
}

// Adds record r to the cell of `key` (new or not), as the device adds it; returns the cell's index.
std::uint32_t AddToCell(const KeyResult& key, const Record& r, const FilterConfig& config, float scale,
                        double square_scale, std::map<std::array<std::uint32_t, 6>, std::uint32_t>& cell_of_key,
                        FilterResult& result) {
  const bool fixed = IntegerSums(config.accumulation);
  const bool packed = config.accumulation == Accumulation::kPackedDecimal;
  FilterStats& stats = result.stats;
  const shared::KeyWords& w = key.words;
  const std::array<std::uint32_t, 6> words = {w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra};
  auto [it, inserted] = cell_of_key.emplace(words, static_cast<std::uint32_t>(result.cells.size()));
  if (inserted) result.cells.push_back(TableCell{words});
  TableCell& cell = result.cells[it->second];
  for (int c = 0; c < 3; ++c) {
    if (fixed) {
      const std::uint64_t add = shared::ToFixedPoint(r.contribution[c], scale);
      cell.fixed_sum[c] += add;
      if (packed) cell.fixed_sum[c] &= 0xFFFFFFFFu;        // a 32-bit word, as the device's
      stats.fixed_point_wraps += cell.fixed_sum[c] < add;  // only a sequence brighter than its F allowed
    } else {
      cell.float_sum[c] += r.contribution[c];
    }
  }
  if (config.second_moments && fixed) {
    const std::uint64_t add = shared::SquareToFixedPoint(glm::vec3(r.contribution), square_scale);
    cell.fixed_square += add;
    stats.fixed_point_wraps += cell.fixed_square < add;
  }
  if (config.second_moments && !fixed) cell.float_square += shared::SquareAsFloat(glm::vec3(r.contribution));
  if (packed) {  // the count's 24 bits carry into the frame counter, as the device's add of 1 to the word
    const std::uint32_t word = shared::PackCountWord(std::uint32_t(cell.count), cell.frames) + 1u;
    cell.count = shared::PackedCount(word);
    cell.frames = shared::PackedFrames(word);
    stats.count_wraps += cell.count == 0;
  } else {
    stats.count_wraps += ++cell.count == 0;
  }
  cell.last_seen = config.frame;
  return it->second;
}

// The cell record i's resolve reads (core/shared/levels.h): its finest level whose count reaches --min-count.
shared::LevelChoice ChooseCell(const FilterResult& result, const FilterConfig& config, std::size_t i) {
  const std::size_t n = result.placement.size();
  const auto cells = static_cast<std::uint32_t>(result.cells.size());
  shared::LevelChoice choice = shared::NoLevelChosen();
  for (std::uint32_t k = 0; k < config.levels; ++k) {
    const std::uint32_t cell = k == 0 ? result.placement[i] : result.coarser_placement[std::size_t(k - 1) * n + i];
    const std::uint64_t count = cell < cells ? result.cells[cell].count : 0;
    choice = shared::ChooseLevel(choice, k, cell, count, cells, config.min_count);
  }
  return choice;
}

// Several filtered bounces (core/transport.h): the scattered vertices' cells looked up in the exact map before the
// frame (cell_of_key, before any of the frame's adds).
// Without a previous frame (the first, where the transport is forced) the map is empty and every lookup misses.
TransportResult TransportFromPrevious(const RecordBatch& batch, const KeyParams& params, const FilterConfig& config,
                                      const FilterResult* previous,
                                      const std::map<std::array<std::uint32_t, 6>, std::uint32_t>& cell_of_key) {
  const TransportLookup lookup = [&](const shared::KeyWords& w) -> std::optional<FoundCell> {
    const auto it = cell_of_key.find({w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra});
    if (it == cell_of_key.end()) return std::nullopt;
    const TableCell& c = previous->cells[it->second];
    return FoundCell{it->second, {c.fixed_sum, c.float_sum, c.count}};
  };
  return TransportBatch(batch, params, config.accumulation, previous ? previous->stats.fixed_point_bits : 0, lookup);
}

}  // namespace

FilterResult ReferenceFilter(const RecordBatch& given, const FilterConfig& config, const FilterResult* previous,
                             const FrameEffects* effects) {
  CheckBatchShape(given);
  CheckScatteredShape(given);
  config.Validate();
  const float footprint = FootprintScale(config.filter_width_px, given.fov_y_radians, given.height);
  const KeyParams params = MakeKeyParams(config, footprint, static_cast<std::uint32_t>(given.records.size()));
  const FrameEffects planned = effects ? *effects : PlanFrameEffects(config, previous ? kLaterFrame : 0);

  FilterResult result;
  FilterStats& stats = result.stats;
  std::map<std::array<std::uint32_t, 6>, std::uint32_t> cell_of_key;  // the table's cells, the previous frame's first
  if (previous) {
    result.cells = previous->cells;
    for (std::size_t c = 0; c < result.cells.size(); ++c) cell_of_key.emplace(result.cells[c].key, std::uint32_t(c));
  }
  std::optional<TransportResult> transport;
  if (planned.transport) {
    transport = TransportFromPrevious(given, params, config, previous, cell_of_key);
    result.transport_read = std::move(transport->read);
    stats.transport = transport->stats;
  }
  const RecordBatch& batch = transport ? transport->batch : given;
  const TableRecords table(batch);  // the records then the deeper ones; only the records are resolved into pixels
  const std::span<const Record> all = table.all();
  stats.records = all.size();
  const bool packed = config.accumulation == Accumulation::kPackedDecimal;
  stats.fixed_point_bits = packed                    ? 0
                           : previous                ? previous->stats.fixed_point_bits
                           : config.fixed_point_bits ? *config.fixed_point_bits
                                                     : ChooseFixedPointBits(all, config.SumHeadroom());
  const float scale = SumScale(config.accumulation, stats.fixed_point_bits);
  const bool fixed = IntegerSums(config.accumulation);
  if (config.accumulation == Accumulation::kFloat32) RequireFloat32Range(stats.fixed_point_bits);
  if (config.accumulation == Accumulation::kFixed64) RequireFixedPointConverts(all, stats.fixed_point_bits);
  if (packed) RequirePackedDecimalConverts(all);
  if (config.second_moments) {
    stats.square_bits = previous             ? previous->stats.square_bits
                        : config.square_bits ? *config.square_bits
                                             : ChooseSquareBits(all, config.SquareHeadroom());
    if (fixed) RequireSquaresConvert(all, stats.square_bits);
    if (!fixed) RequireFloat32SquaresRange(stats.square_bits);
  }
  const double square_scale = std::ldexp(1.0, stats.square_bits);

  result.placement.assign(all.size(), kNoCell);
  result.coarser_placement.assign(std::size_t(config.levels - 1) * all.size(), kNoCell);
  std::vector<KeyResult> keys(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Record& r = all[i];
    const InputVerdict verdict = CheckRecordInputs(r);
    if (verdict == InputVerdict::kNonFinite) ++stats.rejected_non_finite;
    if (verdict == InputVerdict::kNegative) ++stats.rejected_negative;
    if (verdict != InputVerdict::kAccepted) continue;
    if (!shared::RecordHasVertex(r)) {
      ++stats.records_without_vertex;
      continue;
    }
    ++stats.records_with_vertex;
    keys[i] = shared::ComputeKey(params, r);
    if (keys[i].status == shared::kKeyUnkeyable) {
      ++stats.unkeyable;
      continue;
    }
    for (std::uint32_t k = 0; k < config.levels; ++k) {
      const std::uint32_t cell =
          AddToCell(shared::KeyAtLevel(params, keys[i], k), r, config, scale, square_scale, cell_of_key, result);
      (k == 0 ? result.placement[i] : result.coarser_placement[std::size_t(k - 1) * all.size() + i]) = cell;
    }
  }
  if (planned.level_seed) SeedNewCells(config, previous, cell_of_key, result);
  if (planned.temporal) BlendCells(config, previous ? previous->cells : std::vector<TableCell>{}, result);
  if (packed) SettleCells(result);
  if (planned.eviction) EvictCells(config, result);

  std::vector<glm::dvec3> averages(result.cells.size());
  for (std::size_t c = 0; c < result.cells.size(); ++c) {
    const TableCell& cell = result.cells[c];
    for (int k = 0; k < 3; ++k) {
      const double sum = fixed ? IntegerSumValue(cell.fixed_sum[k], config.accumulation, stats.fixed_point_bits)
                               : double(cell.float_sum[k]);
      averages[c][k] = sum / double(cell.count);
    }
    stats.max_records_per_cell = std::max(stats.max_records_per_cell, cell.count);
  }
  // --interpolation: each cell's weight, from its sums and square sum (core/cell_interpolation.h).
  std::vector<double> weights(config.interpolation.enabled() ? result.cells.size() : 0);
  for (std::size_t c = 0; c < weights.size(); ++c) {
    const TableCell& cell = result.cells[c];
    weights[c] =
        CellWeight(config.interpolation, config.accumulation, cell.fixed_sum, cell.float_sum, cell.fixed_square,
                   cell.float_square, cell.count, stats.fixed_point_bits, stats.square_bits);
  }
  stats.cells = result.cells.size();
  std::uint64_t in_cells = 0;  // every frame's, in a sequence
  for (const TableCell& cell : result.cells) in_cells += cell.count;
  stats.mean_records_per_cell = stats.cells ? double(in_cells) / double(stats.cells) : 0.0;

  std::vector<std::optional<glm::dvec3>> cell_average(batch.records.size());
  stats.resolved_at_level.assign(config.levels, 0);
  std::map<std::array<std::uint32_t, 6>, std::uint32_t> live_cell_of_key;  // after eviction's renumbering
  if (config.neighbour_search) {
    for (std::size_t c = 0; c < result.cells.size(); ++c) {
      if (result.cells[c].count > 0) live_cell_of_key.emplace(result.cells[c].key, std::uint32_t(c));
    }
  }
  const CellFinder find = [&](const shared::KeyWords& w) -> std::optional<std::uint32_t> {
    const auto it = live_cell_of_key.find({w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra});
    return it == live_cell_of_key.end() ? std::nullopt : std::optional<std::uint32_t>(it->second);
  };
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    const shared::LevelChoice chosen = ChooseCell(result, config, i);
    if (chosen.slot == kNoCell) continue;
    ++stats.resolved_at_level[chosen.level];
    if (!Searches(config.neighbour_search, chosen, kNoCell)) {
      cell_average[i] = weights.empty() ? averages[chosen.slot]
                                        : Interpolated(config.interpolation, weights[chosen.slot],
                                                       averages[chosen.slot], OwnLight(batch, i));
      continue;
    }
    const NeighbourReads reads = SearchNeighbours(params, batch.records[i], chosen, std::uint32_t(i), find);
    StencilTotal total;
    const auto add = [&](std::uint32_t cell) {
      total.Add(result.cells[cell].fixed_sum, result.cells[cell].float_sum, result.cells[cell].count);
    };
    add(chosen.slot);
    for (const std::uint32_t cell : reads.cells) {
      if (cell == kNotRead) continue;
      add(cell);
      ++stats.neighbours_read;
    }
    cell_average[i] = total.Average(config.accumulation, stats.fixed_point_bits);
    ++stats.records_searched;
    result.neighbour_reads.push_back(reads);
  }
  result.image = ResolvePixels(batch, cell_average);
  return result;
}

Image UnfilteredImage(const RecordBatch& batch) {
  return ResolvePixels(batch, std::vector<std::optional<glm::dvec3>>(batch.records.size()));
}

}  // namespace hpsf
