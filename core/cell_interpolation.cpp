#include "core/cell_interpolation.h"

#include <cmath>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/hash_table.h"
#include "core/number_list.h"
#include "core/shared/cell_interpolation.h"

namespace hpsf {

std::string CellInterpolation::ToString() const {
  if (function == shared::kInterpolationOff) return "off";
  if (function == shared::kInterpolationPath) return "path";
  return std::string(function == shared::kInterpolationStep ? "step:" : "smooth:") + FormatDouble(v0) + ":" +
         FormatDouble(v1);
}

CellInterpolation ParseInterpolation(const std::string& text) {
  if (text == "off") return {};
  if (text == "path") return {shared::kInterpolationPath, 0.0, 1.0};
  const std::string usage = "expected off, path, step:V0:V1 or smooth:V0:V1";
  CellInterpolation interpolation;
  std::size_t from = 0;
  if (text.rfind("step:", 0) == 0) {
    interpolation.function = shared::kInterpolationStep;
    from = 5;
  } else if (text.rfind("smooth:", 0) == 0) {
    interpolation.function = shared::kInterpolationSmooth;
    from = 7;
  } else {
    throw ConfigError("--interpolation", usage + "; got '" + text + "'");
  }
  const std::optional<std::vector<double>> values = ParseNumberList(text, from);
  if (!values || values->size() != 2) throw ConfigError("--interpolation", usage + "; got '" + text + "'");
  interpolation.v0 = (*values)[0];
  interpolation.v1 = (*values)[1];
  if (!(std::isfinite(interpolation.v0) && std::isfinite(interpolation.v1) && interpolation.v0 >= 0.0 &&
        interpolation.v0 < interpolation.v1)) {
    throw ConfigError("--interpolation", "the variance thresholds need 0 <= V0 < V1, both finite; got '" + text + "'");
  }
  if (interpolation.function == shared::kInterpolationSmooth && !(interpolation.v1 - interpolation.v0 < 8.0)) {
    throw ConfigError("--interpolation",
                      "smooth needs V1 - V0 below 8 (eq. 4.5's least weight is (V1 - V0) / 8); got '" + text + "'");
  }
  return interpolation;
}

double CellWeight(const CellInterpolation& interpolation, Accumulation accumulation,
                  const std::array<std::uint64_t, 3>& fixed_sum, const std::array<float, 3>& float_sum,
                  std::uint64_t fixed_square, float float_square, std::uint64_t count, int fixed_point_bits,
                  int square_bits) {
  const bool fixed = accumulation == Accumulation::kFixed64;
  glm::dvec3 sums;
  for (int c = 0; c < 3; ++c) {
    sums[c] = fixed ? double(fixed_sum[c]) * std::ldexp(1.0, -fixed_point_bits) : double(float_sum[c]);
  }
  const double square = fixed ? double(fixed_square) * std::ldexp(1.0, -square_bits) : double(float_square);
  const double variance = shared::SlotVariance(sums, square, double(count));
  return shared::InterpolationWeight(interpolation.function, interpolation.v0, interpolation.v1, variance);
}

double SlotWeight(const CellInterpolation& interpolation, const HashTableDump& table, std::uint32_t slot) {
  const bool fixed = table.accumulation == Accumulation::kFixed64;
  return CellWeight(interpolation, table.accumulation, fixed ? table.fixed_sums[slot] : std::array<std::uint64_t, 3>{},
                    fixed ? std::array<float, 3>{} : table.float_sums[slot], fixed ? table.fixed_squares[slot] : 0,
                    fixed ? 0.0f : table.float_squares[slot], table.counts[slot], table.fixed_point_bits,
                    table.square_bits);
}

glm::dvec3 Interpolated(const CellInterpolation& interpolation, double weight, const glm::dvec3& average,
                        const glm::dvec3& own) {
  if (!interpolation.enabled()) return average;
  return shared::InterpolatedIncident(weight, average, own);
}

}  // namespace hpsf
