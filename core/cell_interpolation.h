// --interpolation (Schipek §4.1.2; the weight is core/shared/cell_interpolation.h): the resolve blends each record's
// own light with its cell's average by a weight of the cell's variance. Parsed here, applied where each backend and
// the contract resolve a record, from the slot or cell the record reads (the variance of that cell alone: a searching
// resolve's stencil is refused with interpolation).
#ifndef HPSF_CORE_CELL_INTERPOLATION_H
#define HPSF_CORE_CELL_INTERPOLATION_H

#include <array>
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "core/accumulation.h"

namespace hpsf {

struct HashTableDump;  // core/hash_table.h

struct CellInterpolation {
  std::uint32_t function =
      0;  // shared::kInterpolationOff, kInterpolationStep, kInterpolationSmooth or kInterpolationPath
  double v0 = 0.0;
  double v1 = 1.0;
  bool enabled() const { return function != 0; }
  std::string ToString() const;  // "off", "path", "step:V0:V1" or "smooth:V0:V1"
  bool operator==(const CellInterpolation&) const = default;
};

// "off", "path" (w = 0: each record's own light), "step:V0:V1" (eq. 4.4) or "smooth:V0:V1" (eq. 4.5) with 0 <= V0 < V1
// finite (smooth: V1 - V0 < 8, where eq. 4.5's least weight (V1 - V0) / 8 stays below 1); a ConfigError naming
// --interpolation otherwise.
CellInterpolation ParseInterpolation(const std::string& text);

// The weight of a cell of these sums (fixed64 words at 2^F and a square word at 2^G, or float32's floats) and count.
double CellWeight(const CellInterpolation& interpolation, Accumulation accumulation,
                  const std::array<std::uint64_t, 3>& fixed_sum, const std::array<float, 3>& float_sum,
                  std::uint64_t fixed_square, float float_square, std::uint64_t count, int fixed_point_bits,
                  int square_bits);
// The weight of a hashed table's slot (its second moments kept).
double SlotWeight(const CellInterpolation& interpolation, const HashTableDump& table, std::uint32_t slot);

// What a record's vertex receives: its cell's average where interpolation is off, else w average + (1 - w) own.
glm::dvec3 Interpolated(const CellInterpolation& interpolation, double weight, const glm::dvec3& average,
                        const glm::dvec3& own);

}  // namespace hpsf

#endif  // HPSF_CORE_CELL_INTERPOLATION_H
