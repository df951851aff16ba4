// The variance of each cell (--second-moments, core/cell_moments.h) of the reference's exact map, summarized for
// `hpsf stats` and laid out per pixel for `hpsf render`'s debug image.
#ifndef HPSF_VERIFIER_METRICS_CELL_VARIANCE_H
#define HPSF_VERIFIER_METRICS_CELL_VARIANCE_H

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/accumulation.h"
#include "core/cell_moments.h"
#include "core/filter_result.h"
#include "core/hashed_run.h"
#include "core/record.h"

namespace hpsf {

// Over the cells that hold two or more samples (a variance of one sample is 0 by definition, and says nothing).
struct CellVarianceSummary {
  std::uint64_t cells = 0;
  std::uint64_t resolved = 0;  // whose variance stands clear of its rounding bound (CellMoments::Resolved)
  double median_variance = 0.0, p90_variance = 0.0, max_variance = 0.0;
  // The relative standard error of a cell's mean, sqrt(variance / count) / mean, at its median over cells with a
  // positive mean: how converged the table's cells are.
  double median_relative_error = 0.0;
  // Cells per decade of variance: [k] counts 10^(kLowestDecade + k) <= variance < 10^(kLowestDecade + k + 1), the
  // first also everything below, the last everything above.
  static constexpr int kLowestDecade = -8;
  std::vector<std::uint64_t> decades;
  nlohmann::json ToJson() const;
};

CellMoments MomentsOfCell(const TableCell& cell, Accumulation accumulation, const FilterStats& stats);
// A hashed table's slot (one that keeps second moments), read as MomentsOfCell reads an exact cell.
CellMoments MomentsOfSlot(const HashTableDump& table, std::uint32_t slot);

// The exact map of a run with second moments (ReferenceFilter with config.second_moments).
CellVarianceSummary SummarizeCellVariance(const FilterResult& exact, Accumulation accumulation);

// Per pixel, the mean over its samples of the variance of the cell each sample's record resolves from (its own
// level's cell); 0 for a pixel with none. Row-major, batch.width x batch.height.
std::vector<float> CellVariancePerPixel(const RecordBatch& batch, const FilterResult& exact, Accumulation accumulation);
// The same from a hashed backend's own table: each record's slot.
std::vector<float> CellVariancePerPixel(const RecordBatch& batch, const HashedRun& run);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_CELL_VARIANCE_H
