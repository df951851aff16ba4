// A cell's moments read back from its sums (--second-moments): the mean brightness y = r + g + b and the mean square
// y^2 of its samples, the variance of its channel mean (core/shared/second_moment.h) and a bound on that variance's
// error, so that a report can tell a variance from rounding noise.
//
// The bound covers a cell whose sums are the sums of its samples (one frame, or frames integrated): in fixed64 the
// rounding of each sample's channels at 2^-F and its square at 2^-G, and the readout's double arithmetic; in float32
// the checker's bound on each float sum, gamma(n) = n u / (1 - n u) with u = 2^-23, and the float square of each
// sample. In float32 the bound grows with E[y^2], not with the variance: a bright, nearly constant cell has a variance
// far below it, where fixed64 still resolves it (docs/design/algorithm.md#second-moments).
#ifndef HPSF_CORE_CELL_MOMENTS_H
#define HPSF_CORE_CELL_MOMENTS_H

#include <array>
#include <cstdint>

#include "core/accumulation.h"

namespace hpsf {

struct CellMoments {
  double mean_brightness = 0.0;  // E[y]
  double mean_square = 0.0;      // E[y^2]
  double variance = 0.0;         // of the channel mean y / 3: (E[y^2] - E[y]^2) / 9, at least 0
  double variance_bound = 0.0;   // |variance - the samples' exact variance| is at most this
  // The variance stands clear of its rounding: variance > variance_bound.
  bool Resolved() const { return variance > variance_bound; }
};

// From a cell's sums and count (count >= 1): fixed_sum and fixed_square in fixed64 (at 2^F and 2^G), float_sum and
// float_square in float32. packed-decimal keeps no squares.
CellMoments MomentsOf(Accumulation accumulation, const std::array<std::uint64_t, 3>& fixed_sum,
                      const std::array<float, 3>& float_sum, std::uint64_t fixed_square, float float_square,
                      std::uint64_t count, int fixed_point_bits, int square_bits);

}  // namespace hpsf

#endif  // HPSF_CORE_CELL_MOMENTS_H
