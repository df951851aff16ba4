#include "core/temporal.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/format.h"
#include "core/shared/packed_sums.h"

namespace hpsf {

std::string Temporal::ToString() const {
  switch (mode) {
    case TemporalMode::kIntegrate:
      return "integrate";
    case TemporalMode::kEma:
      return "ema:" + FormatDouble(alpha) + (max_count ? ":" + std::to_string(max_count) : std::string());
    case TemporalMode::kAdaptive:
      return "adaptive";
    case TemporalMode::kAdaptiveVariance:
      return "adaptive-variance";
  }
  return "?";
}

Temporal ParseTemporal(const std::string& text) {
  if (text == "integrate") return {};
  if (text == "adaptive") return {TemporalMode::kAdaptive, 1.0, 0};
  if (text == "adaptive-variance") return {TemporalMode::kAdaptiveVariance, 1.0, 0};
  const std::string prefix = "ema:";
  if (text.rfind(prefix, 0) != 0) {
    throw ConfigError("--temporal",
                      "expected integrate, ema:ALPHA[:MAXCOUNT], adaptive or adaptive-variance; got '" + text + "'");
  }
  const char* first = text.data() + prefix.size();
  const char* last = text.data() + text.size();
  Temporal temporal{TemporalMode::kEma, 0.0, 0};
  auto [end, error] = std::from_chars(first, last, temporal.alpha);
  if (error != std::errc() || end == first || !(temporal.alpha > 0.0 && temporal.alpha <= 1.0)) {
    throw ConfigError("--temporal", "ema needs ALPHA in (0, 1], as in ema:0.9 or ema:0.9:64; got '" + text + "'");
  }
  if (end == last) return temporal;
  if (*end != ':') throw ConfigError("--temporal", "expected ema:ALPHA[:MAXCOUNT]; got '" + text + "'");
  const char* count_first = end + 1;
  auto [count_end, count_error] = std::from_chars(count_first, last, temporal.max_count);
  if (count_error != std::errc() || count_end != last || count_end == count_first || temporal.max_count == 0) {
    throw ConfigError("--temporal", "ema's MAXCOUNT must be an integer >= 1, as in ema:0.9:64; got '" + text + "'");
  }
  return temporal;
}

shared::TemporalParams MakeTemporalParams(const Temporal& temporal, Accumulation accumulation, int fixed_point_bits,
                                          int square_bits) {
  shared::TemporalParams p{};
  p.mode = temporal.mode == TemporalMode::kIntegrate  ? shared::kTemporalIntegrate
           : temporal.mode == TemporalMode::kEma      ? shared::kTemporalEma
           : temporal.mode == TemporalMode::kAdaptive ? shared::kTemporalAdaptive
                                                      : shared::kTemporalAdaptiveVariance;
  p.square_shift = accumulation == Accumulation::kFixed64 ? 2 * fixed_point_bits - square_bits : 0;
  p.alpha = temporal.mode == TemporalMode::kEma ? temporal.alpha : 1.0;
  p.max_count = temporal.max_count ? temporal.max_count : std::numeric_limits<std::uint64_t>::max();
  return p;
}

CellState BlendCellState(const shared::TemporalParams& params, Accumulation sums, const CellState& before,
                         const CellState& accumulated) {
  const bool integer = IntegerSums(sums);
  const bool packed = sums == Accumulation::kPackedDecimal;
  const std::uint64_t word_mask = packed ? 0xFFFFFFFFu : ~std::uint64_t(0);
  const std::uint64_t count_mask = packed ? shared::kPackedCountMask : ~std::uint64_t(0);
  glm::dvec3 old_sum, frame_sum;
  for (int c = 0; c < 3; ++c) {
    old_sum[c] = integer ? double(before.fixed_sum[c]) : double(before.float_sum[c]);
    frame_sum[c] = integer ? double((accumulated.fixed_sum[c] - before.fixed_sum[c]) & word_mask)
                           : double(accumulated.float_sum[c] - before.float_sum[c]);
  }
  const double old_square = integer ? double(before.fixed_square) : double(before.float_square);
  const double frame_square = integer ? double(accumulated.fixed_square - before.fixed_square)
                                      : double(accumulated.float_square - before.float_square);
  const std::uint64_t frame_count = (accumulated.count - before.count) & count_mask;
  const shared::TemporalBlend blend =
      shared::BlendCell(params, old_sum, before.count, frame_sum, frame_count, old_square, frame_square);
  if (blend.integrated) return accumulated;
  CellState blended;
  blended.count = blend.count & count_mask;
  const double square = shared::BlendSquare(blend, old_square, before.count, frame_square, frame_count);
  const double rounded_square = shared::RoundHalfEvenNonNegative(square);
  blended.fixed_square = integer ? (rounded_square < 0x1p64 ? std::uint64_t(rounded_square) : ~std::uint64_t(0)) : 0;
  blended.float_square = integer ? 0.0f : float(square);
  for (int c = 0; c < 3; ++c) {
    if (integer) {
      // Saturated: a broken kernel's table (D10) can ask for sums beyond 2^64, whose conversion would be undefined.
      const double rounded = shared::RoundHalfEvenNonNegative(blend.sum[c]);
      blended.fixed_sum[c] = (rounded < 0x1p64 ? std::uint64_t(rounded) : ~std::uint64_t(0)) & word_mask;
    } else {
      blended.float_sum[c] = float(blend.sum[c]);
    }
  }
  return blended;
}

}  // namespace hpsf
