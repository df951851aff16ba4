// Temporal accumulation across frames (Binder et al. §3.4.1, Schipek §5.3): how a cell blends what it
// held before a frame (its history: average h over N_old samples) with what the frame added (average f over
// N_new). integrate weighs them by their counts, alpha = N_old / (N_old + N_new): the table holds every frame's
// exact sums. ema:ALPHA[:MAXCOUNT] caps the history's weight: alpha = min(ALPHA, N' / (N' + N_new)) with
// N' = min(N_old, MAXCOUNT), so a young cell still integrates (a plain EMA of a cell with few samples never
// converges, Binder §3.4.1) and an old one forgets at the rate ALPHA sets (ALPHA 1 with MAXCOUNT is Schipek's
// maximum cell count). adaptive lowers the integration's alpha by the cell's temporal change, the largest
// relative difference |f - h| / (f + h) of a channel: alpha = N_old / (N_old + N_new) * (1 - change), so a cell
// whose light changed forgets and a steady one integrates (Binder's Fig. 9c). adaptive-variance (--second-moments)
// takes a change for noise while the brightness's |f - h| stays within two standard deviations of the noise the
// cell's variance predicts, and scales the change down by how much of |f - h|^2 that noise explains (Schipek §4.1's
// variance put to Binder's heuristic): at 1 spp adaptive forgets at noise, adaptive-variance does not. The blend
// itself is shared by C++ and GLSL: core/shared/temporal_blend.h.
#ifndef HPSF_CORE_TEMPORAL_H
#define HPSF_CORE_TEMPORAL_H

#include <array>
#include <cstdint>
#include <string>

#include "core/accumulation.h"
#include "core/shared/temporal_blend.h"

namespace hpsf {

enum class TemporalMode { kIntegrate, kEma, kAdaptive, kAdaptiveVariance };

struct Temporal {
  TemporalMode mode = TemporalMode::kIntegrate;
  double alpha = 1.0;           // ema: the largest weight of the history, in (0, 1]
  std::uint64_t max_count = 0;  // ema: the cap on the history's count; 0 for none

  bool blends() const { return mode != TemporalMode::kIntegrate; }
  // adaptive or adaptive-variance: the history's weight follows the cell's averages
  bool adapts() const { return mode == TemporalMode::kAdaptive || mode == TemporalMode::kAdaptiveVariance; }
  std::string ToString() const;  // "integrate", "ema:0.9", "ema:0.9:64", "adaptive", "adaptive-variance"
  bool operator==(const Temporal&) const = default;
};

// Parses "integrate", "ema:ALPHA" or "ema:ALPHA:MAXCOUNT" (ALPHA in (0, 1], MAXCOUNT >= 1), "adaptive" or
// "adaptive-variance"; a ConfigError naming --temporal otherwise.
Temporal ParseTemporal(const std::string& text);

// The shared blend's parameters for `temporal` over a table of these sums, at F and G (adaptive-variance's square
// shift: 2F - G for fixed64, 0 for float32).
shared::TemporalParams MakeTemporalParams(const Temporal& temporal, Accumulation accumulation, int fixed_point_bits,
                                          int square_bits);

// A cell's sums and count in the table's own types: integer sums (fixed64, or packed-decimal's 32-bit words) or
// float32 sums.
struct CellState {
  std::array<std::uint64_t, 3> fixed_sum{};
  std::array<float, 3> float_sum{};
  std::uint64_t count = 0;
  // --second-moments: the square sum (core/shared/second_moment.h), blended as the sums are
  std::uint64_t fixed_square = 0;
  float float_square = 0.0f;
};

// The cell after the frame's blend, from the cell before the frame (count >= 1) and after the frame's accumulate
// (a larger count), as every backend computes it: the frame's sums are the difference (exact in integer sums), the
// blend is shared::BlendCell, and its sums round half to even (integer sums) or to the nearest float.
// packed-decimal's words wrap as the device's do: the differences and the blended words are taken modulo 2^32 (the
// count modulo 2^24). The blend runs before the settle, which would halve the history out of the difference.
CellState BlendCellState(const shared::TemporalParams& params, Accumulation sums, const CellState& before,
                         const CellState& accumulated);

}  // namespace hpsf

#endif  // HPSF_CORE_TEMPORAL_H
