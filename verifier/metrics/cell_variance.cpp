#include "verifier/metrics/cell_variance.h"

#include <algorithm>
#include <cmath>

namespace hpsf {
namespace {

constexpr int kDecades = 14;  // 1e-8 .. 1e6

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const std::size_t k = std::min(values.size() - 1, std::size_t(std::ceil(q * double(values.size()))) - 1);
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
  return values[k];
}

// Per pixel, the mean over its samples of variance_of(record), which is negative for a record without a cell.
template <typename VarianceOf>
std::vector<float> PerPixel(const RecordBatch& batch, const VarianceOf& variance_of) {
  std::vector<float> pixels(std::size_t(batch.width) * batch.height, 0.0f);
  const std::size_t spp = batch.samples_per_pixel;
  for (std::size_t pixel = 0; pixel < pixels.size(); ++pixel) {
    double sum = 0.0;
    std::size_t samples = 0;
    for (std::size_t s = 0; s < spp; ++s) {
      const double variance = variance_of(pixel * spp + s);
      if (variance < 0.0) continue;
      sum += variance;
      ++samples;
    }
    pixels[pixel] = samples ? float(sum / double(samples)) : 0.0f;
  }
  return pixels;
}

}  // namespace

CellMoments MomentsOfCell(const TableCell& cell, Accumulation accumulation, const FilterStats& stats) {
  return MomentsOf(accumulation, cell.fixed_sum, cell.float_sum, cell.fixed_square, cell.float_square, cell.count,
                   stats.fixed_point_bits, stats.square_bits);
}

CellMoments MomentsOfSlot(const HashTableDump& t, std::uint32_t slot) {
  const bool fixed = t.accumulation == Accumulation::kFixed64;
  return MomentsOf(t.accumulation, fixed ? t.fixed_sums[slot] : std::array<std::uint64_t, 3>{},
                   fixed ? std::array<float, 3>{} : t.float_sums[slot], fixed ? t.fixed_squares[slot] : 0,
                   fixed ? 0.0f : t.float_squares[slot], t.counts[slot], t.fixed_point_bits, t.square_bits);
}

CellVarianceSummary SummarizeCellVariance(const FilterResult& exact, Accumulation accumulation) {
  CellVarianceSummary s;
  s.decades.assign(kDecades, 0);
  std::vector<double> variances, relative_errors;
  for (const TableCell& cell : exact.cells) {
    if (cell.count < 2) continue;
    const CellMoments m = MomentsOfCell(cell, accumulation, exact.stats);
    ++s.cells;
    s.resolved += m.Resolved();
    variances.push_back(m.variance);
    const double mean = m.mean_brightness / 3.0;
    if (mean > 0.0) relative_errors.push_back(std::sqrt(m.variance / double(cell.count)) / mean);
    const int decade = m.variance > 0.0 ? int(std::floor(std::log10(m.variance))) : CellVarianceSummary::kLowestDecade;
    ++s.decades[std::size_t(std::clamp(decade - CellVarianceSummary::kLowestDecade, 0, kDecades - 1))];
  }
  s.median_variance = Quantile(variances, 0.5);
  s.p90_variance = Quantile(variances, 0.9);
  s.max_variance = variances.empty() ? 0.0 : *std::max_element(variances.begin(), variances.end());
  s.median_relative_error = Quantile(relative_errors, 0.5);
  return s;
}

nlohmann::json CellVarianceSummary::ToJson() const {
  nlohmann::json decade_counts = nlohmann::json::array();
  for (std::size_t k = 0; k < decades.size(); ++k) {
    decade_counts.push_back({{"from", std::pow(10.0, kLowestDecade + int(k))}, {"cells", decades[k]}});
  }
  return {{"cells", cells},
          {"resolved", resolved},
          {"median_variance", median_variance},
          {"p90_variance", p90_variance},
          {"max_variance", max_variance},
          {"median_relative_error", median_relative_error},
          {"decades", decade_counts}};
}

std::vector<float> CellVariancePerPixel(const RecordBatch& batch, const FilterResult& exact,
                                        Accumulation accumulation) {
  std::vector<double> cell_variance(exact.cells.size());
  for (std::size_t c = 0; c < exact.cells.size(); ++c) {
    cell_variance[c] = MomentsOfCell(exact.cells[c], accumulation, exact.stats).variance;
  }
  return PerPixel(batch, [&](std::size_t i) {
    const std::uint32_t cell = exact.placement[i];
    return cell < cell_variance.size() ? cell_variance[cell] : -1.0;
  });
}

std::vector<float> CellVariancePerPixel(const RecordBatch& batch, const HashedRun& run) {
  const HashTableDump& t = run.table;
  if (!t.second_moments) return std::vector<float>(std::size_t(batch.width) * batch.height, 0.0f);
  return PerPixel(batch, [&](std::size_t i) {
    const std::uint32_t slot = run.placements[i];
    return slot < t.capacity && t.counts[slot] > 0 ? MomentsOfSlot(t, slot).variance : -1.0;
  });
}

}  // namespace hpsf
