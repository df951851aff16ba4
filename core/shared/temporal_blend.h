// The temporal blend of one cell after a frame's accumulate (core/temporal.h says what each mode means), shared by
// C++ (the reference, the emulator, the table checker) and GLSL (vulkan/shaders/temporal.comp). In double, with
// correctly rounded adds, multiplies, divides and conversions only (the shader declares round-to-nearest-even for
// 64-bit floats, as resolve does), so every backend blends to the same bits.
//
// The blended cell keeps the table's form, a sum and an integer count: the average alpha h + (1 - alpha) f over
// a count N = ceil(N_new / (1 - alpha)), the count whose integration weight N / (N + N_new') matches alpha at the
// next frame's like-sized add, at most N' + N_new. Its sum, average times count, never exceeds the integrated
// sum S_old + S_new by more than one average (alpha <= N' / (N' + N_new)), so fixed64's F, chosen for integrating
// `frames` frames, holds for every mode. When alpha is the integration's own, the blend is integration and the
// table keeps its exact sums.
#ifndef HPSF_CORE_SHARED_TEMPORAL_BLEND_H
#define HPSF_CORE_SHARED_TEMPORAL_BLEND_H

#include "exact_rounding.h"
#include "prelude.h"

HPSF_SHARED_BEGIN

const uint kTemporalIntegrate = 0u;
const uint kTemporalEma = 1u;
const uint kTemporalAdaptive = 2u;
const uint kTemporalAdaptiveVariance = 3u;

// The adaptive-variance change judges |f - h| against the noise the cell's variance predicts: a change of the mean
// brightness within kTemporalNoiseZ standard deviations of that noise is taken for noise (z^2 = 4: two deviations).
const double kTemporalNoiseZSquared = 4.0;

struct TemporalParams {
  double alpha;        // ema: the largest weight of the history; 1 otherwise
  uint64_t max_count;  // the cap on the history's count; 2^64 - 1 for none
  uint mode;           // kTemporalIntegrate, kTemporalEma, kTemporalAdaptive or kTemporalAdaptiveVariance
  // adaptive-variance: 2F - G, the shift that takes a square sum (at 2^G) to the squared sums' units (2^2F); 0 for
  // float32, whose sums and squares are both plain floats
  int square_shift;
};

struct TemporalBlend {
  dvec3 sum;        // the cell's new sums, to be rounded to the table's type (unless integrated)
  uint64_t count;   // the cell's new count
  bool integrated;  // alpha is the integration's: the cell keeps its exact sums, S_old + S_new
  double alpha;     // the history's weight, and the count as a double: what BlendSquare blends with
  double weight;
};

// The largest relative change of a channel between the history's average h and the frame's f, in [0, 1]: 0 when
// both are 0.
HPSF_FN double TemporalChange(dvec3 h, dvec3 f) {
  double change = double(0.0);
  for (int c = 0; c < 3; ++c) {
    HPSF_PRECISE double total = h[c] + f[c];
    HPSF_PRECISE double difference = f[c] > h[c] ? f[c] - h[c] : h[c] - f[c];
    HPSF_PRECISE double relative = total > double(0.0) ? difference / total : double(0.0);
    change = relative > change ? relative : change;
  }
  return change;
}

// adaptive-variance's change: TemporalChange scaled by how far the squared difference d^2 of the mean brightness
// (r + g + b) of history and frame stands above z^2 times the noise it would have if the light had not changed,
// V (1 / n + 1 / N'), with V the variance of one sample's brightness within the history and within the frame, pooled
// (from the square sums, each about its own mean): 0 within z deviations, rising to TemporalChange as d^2 outgrows the
// noise, 1 - z^2 noise / d^2. No square root: d^2 is compared with z^2 noise. Sums in the table's units, squares at
// theirs (square_shift).
HPSF_FN double TemporalNoiseChange(TemporalParams p, dvec3 old_sum, uint64_t old_count, dvec3 frame_sum,
                                   uint64_t frame_count, double weight, double old_square, double frame_square) {
  HPSF_PRECISE double n = double(frame_count);
  HPSF_PRECISE double old_partial = old_sum[0] + old_sum[1];
  HPSF_PRECISE double old_y = old_partial + old_sum[2];
  HPSF_PRECISE double frame_partial = frame_sum[0] + frame_sum[1];
  HPSF_PRECISE double frame_y = frame_partial + frame_sum[2];
  HPSF_PRECISE double h = old_y / double(old_count);
  HPSF_PRECISE double f = frame_y / n;
  HPSF_PRECISE double d = f - h;
  HPSF_PRECISE double d2 = d * d;
  // Each part's squares about its own mean, so that the change itself does not count as noise.
  HPSF_PRECISE double old_squares = ldexp(old_square, p.square_shift);
  HPSF_PRECISE double old_spread = old_squares - old_y * h;
  HPSF_PRECISE double frame_squares = ldexp(frame_square, p.square_shift);
  HPSF_PRECISE double frame_spread = frame_squares - frame_y * f;
  HPSF_PRECISE double spreads = old_spread + frame_spread;
  HPSF_PRECISE double total = double(old_count) + n;
  HPSF_PRECISE double variance = spreads / total;
  variance = variance > double(0.0) ? variance : double(0.0);
  HPSF_PRECISE double inverse_n = double(1.0) / n;
  HPSF_PRECISE double inverse_w = double(1.0) / weight;
  HPSF_PRECISE double spread = inverse_n + inverse_w;
  HPSF_PRECISE double noise = variance * spread;
  HPSF_PRECISE double threshold = noise * kTemporalNoiseZSquared;
  if (!(d2 > threshold)) return double(0.0);
  HPSF_PRECISE double explained = threshold / d2;
  HPSF_PRECISE double scale = double(1.0) - explained;
  HPSF_PRECISE double change = TemporalChange(old_sum / double(old_count), frame_sum / n) * scale;
  return change;
}

// old_sum, old_count: the cell before the frame (old_count >= 1); frame_sum, frame_count: what the frame added
// (frame_count >= 1). Sums in the table's units (fixed64: scaled by 2^F). old_square, frame_square: the square sums
// of the history and the frame (--second-moments; read by adaptive-variance only, 0 otherwise).
HPSF_FN TemporalBlend BlendCell(TemporalParams p, dvec3 old_sum, uint64_t old_count, dvec3 frame_sum,
                                uint64_t frame_count, double old_square, double frame_square) {
  uint64_t capped = old_count < p.max_count ? old_count : p.max_count;
  HPSF_PRECISE double n = double(frame_count);
  HPSF_PRECISE double w = double(capped);
  HPSF_PRECISE dvec3 h = old_sum / double(old_count);
  HPSF_PRECISE dvec3 f = frame_sum / n;
  HPSF_PRECISE double integration = w / (w + n);
  HPSF_PRECISE double alpha = integration;
  if (p.mode == kTemporalEma && p.alpha < integration) alpha = p.alpha;
  if (p.mode == kTemporalAdaptive) alpha = integration * (double(1.0) - TemporalChange(h, f));
  if (p.mode == kTemporalAdaptiveVariance) {
    HPSF_PRECISE double change =
        TemporalNoiseChange(p, old_sum, old_count, frame_sum, frame_count, w, old_square, frame_square);
    alpha = integration * (double(1.0) - change);
  }
  TemporalBlend b;
  b.alpha = alpha;
  b.weight = w + n;
  if (alpha == integration && capped == old_count) {
    b.sum = old_sum + frame_sum;
    b.count = old_count + frame_count;
    b.integrated = true;
    return b;
  }
  HPSF_PRECISE double most = w + n;
  // +inf when alpha rounded to 1: capped below. Not GLSL's ceil, which lavapipe gets wrong (exact_rounding.h).
  HPSF_PRECISE double weight = CeilNonNegative(n / (double(1.0) - alpha));
  weight = weight < most ? weight : most;
  // The largest double below 2^64: counts a broken kernel wrapped (D12, D10) must still convert to uint64.
  HPSF_PRECISE double largest = double(0xFFFFFFFFFFFFF800ul);
  weight = weight < largest ? weight : largest;
  HPSF_PRECISE dvec3 blended = alpha * h + (double(1.0) - alpha) * f;
  b.sum = blended * weight;
  b.count = uint64_t(weight);
  b.integrated = false;
  b.weight = weight;
  return b;
}

// --second-moments: a cell's square sum (core/shared/second_moment.h) blended as its sums were by b: the mean square
// alpha E_old[y^2] + (1 - alpha) E_frame[y^2] over b's count, or the exact S2_old + S2_new when b integrated.
HPSF_FN double BlendSquare(TemporalBlend b, double old_square, uint64_t old_count, double frame_square,
                           uint64_t frame_count) {
  if (b.integrated) return old_square + frame_square;
  HPSF_PRECISE double h = old_square / double(old_count);
  HPSF_PRECISE double f = frame_square / double(frame_count);
  HPSF_PRECISE double blended = b.alpha * h + (double(1.0) - b.alpha) * f;
  HPSF_PRECISE double square = blended * b.weight;
  return square;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_TEMPORAL_BLEND_H
