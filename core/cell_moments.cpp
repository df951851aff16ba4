#include "core/cell_moments.h"

#include <cmath>

#include "core/shared/second_moment.h"

namespace hpsf {
namespace {

constexpr double kDoubleUnit = 0x1p-53;  // a double's unit roundoff
constexpr double kFloatUnit = 0x1p-23;   // the checker's u for float atomics (not promised to round to nearest)

// The readout's own double arithmetic: a few unit roundoffs of the terms it subtracts.
double ReadoutError(double mean_brightness, double mean_square) {
  return 16.0 * kDoubleUnit * (mean_square + mean_brightness * mean_brightness);
}

}  // namespace

CellMoments MomentsOf(Accumulation accumulation, const std::array<std::uint64_t, 3>& fixed_sum,
                      const std::array<float, 3>& float_sum, std::uint64_t fixed_square, float float_square,
                      std::uint64_t count, int fixed_point_bits, int square_bits) {
  CellMoments m;
  if (count == 0) return m;
  const double n = double(count);
  const bool fixed = accumulation == Accumulation::kFixed64;
  double brightness_error = 0.0, square_error = 0.0;  // bounds on the two means' errors
  if (fixed) {
    const double sum = double(fixed_sum[0]) + double(fixed_sum[1]) + double(fixed_sum[2]);
    m.mean_brightness = std::ldexp(sum, -fixed_point_bits) / n;
    m.mean_square = std::ldexp(double(fixed_square), -square_bits) / n;
    // Each sample's three channels round by half a unit of 2^-F, its square by half of 2^-G (and by a double's
    // roundoff before that).
    brightness_error = 1.5 * std::ldexp(1.0, -fixed_point_bits);
    square_error = 0.5 * std::ldexp(1.0, -square_bits) + 2.0 * kDoubleUnit * m.mean_square;
  } else {
    m.mean_brightness = (double(float_sum[0]) + double(float_sum[1]) + double(float_sum[2])) / n;
    m.mean_square = double(float_square) / n;
    // Each float sum within gamma(n) of its samples' exact sum; each sample's square formed in float (two adds and
    // a multiply, each within u). The means themselves stand in for the exact ones, widened by the same factor.
    const double gamma = n * kFloatUnit / (1.0 - n * kFloatUnit);
    const double relative = gamma + 5.0 * kFloatUnit;
    brightness_error = relative * std::abs(m.mean_brightness) * (1.0 + relative);
    square_error = relative * m.mean_square * (1.0 + relative);
  }
  m.variance = shared::CellVariance(m.mean_brightness, m.mean_square);
  const double brightness_square_error =
      2.0 * std::abs(m.mean_brightness) * brightness_error + brightness_error * brightness_error;
  m.variance_bound = (brightness_square_error + square_error + ReadoutError(m.mean_brightness, m.mean_square)) / 9.0;
  return m;
}

}  // namespace hpsf
