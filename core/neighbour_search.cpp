#include "core/neighbour_search.h"

namespace hpsf {

std::array<shared::KeyWords, shared::kStencilCells - 1> StencilNeighbourWords(const KeyParams& params, const Record& r,
                                                                              const shared::KeyPosition& at,
                                                                              std::uint32_t level) {
  const KeyResult own = shared::KeyAtPosition(params, r, at);
  const glm::uvec3 sides = shared::StencilSidesAtLevel(shared::StencilSidesAtOwnLevel(at), own.words, level);
  const shared::KeyWords cell = shared::KeyAtLevel(params, own, level).words;
  std::array<shared::KeyWords, shared::kStencilCells - 1> words;
  for (std::uint32_t corner = 1; corner < shared::kStencilCells; ++corner) {
    words[corner - 1] = shared::StencilCellWords(cell, sides, corner);
  }
  return words;
}

NeighbourReads SearchNeighbours(const KeyParams& params, const Record& r, const shared::LevelChoice& chosen,
                                std::uint32_t record, const CellFinder& find) {
  NeighbourReads reads;
  reads.record = record;
  reads.level = chosen.level;
  reads.cells.fill(kNotRead);
  const auto words = StencilNeighbourWords(params, r, shared::JitteredKeyPosition(params, r), chosen.level);
  for (std::size_t c = 0; c < words.size(); ++c) {
    const std::optional<std::uint32_t> found = find(words[c]);
    if (found) reads.cells[c] = *found;
  }
  return reads;
}

void StencilTotal::Add(const std::array<std::uint64_t, 3>& fixed, const std::array<float, 3>& floating,
                       std::uint64_t n) {
  for (int c = 0; c < 3; ++c) {
    fixed_sum[c] += fixed[c];
    float_sum[c] += double(floating[c]);
  }
  count += n;
}

glm::dvec3 StencilTotal::Average(Accumulation accumulation, int fixed_point_bits) const {
  glm::dvec3 average;
  for (int c = 0; c < 3; ++c) {
    const double sum =
        IntegerSums(accumulation) ? IntegerSumValue(fixed_sum[c], accumulation, fixed_point_bits) : float_sum[c];
    average[c] = sum / double(count);
  }
  return average;
}

}  // namespace hpsf
