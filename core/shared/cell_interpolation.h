// Variance-aware spatial cell interpolation (Schipek §4.1.2, eqs. 4.4 and 4.5), written once for C++ and GLSL: the
// resolve blends a record's own path-traced light with its cell's average, w average + (1 - w) own, by a weight w of
// the cell's variance v (core/shared/second_moment.h). Low and high variance take the cell (w = 1), a middle range
// between the thresholds v0 and v1 takes the path (step, eq. 4.4: w = 0 for v0 < v < v1) or leans to it (smooth, eq.
// 4.5, Schipek's one-over-x-squared shape, w = (v1 - v0) / 8 at the thresholds' midpoint). In double, from correctly
// rounded operations only, so every backend resolves the same bits.
#ifndef HPSF_CORE_SHARED_CELL_INTERPOLATION_H
#define HPSF_CORE_SHARED_CELL_INTERPOLATION_H

#include "prelude.h"
#include "second_moment.h"

HPSF_SHARED_BEGIN

const uint kInterpolationOff = 0u;
const uint kInterpolationStep = 1u;    // eq. 4.4
const uint kInterpolationSmooth = 2u;  // eq. 4.5
const uint kInterpolationPath = 3u;    // w = 0 everywhere: the record's own light (a path graph's, or the path's)

// The cell's weight w in [0, 1] at variance v.
HPSF_FN double InterpolationWeight(uint function, double v0, double v1, double variance) {
  if (function == kInterpolationPath) return double(0.0);
  if (function == kInterpolationStep) return variance > v0 && variance < v1 ? double(0.0) : double(1.0);
  HPSF_PRECISE double width = v1 - v0;
  HPSF_PRECISE double half_sum = (v1 + v0) * double(0.5);
  HPSF_PRECISE double x = (variance - half_sum) / (width * double(2.0));
  HPSF_PRECISE double denominator = x * x * double(16.0) + double(1.0);
  HPSF_PRECISE double numerator = double(1.0) - width / double(8.0);
  HPSF_PRECISE double w = double(1.0) - numerator / denominator;
  w = w < double(0.0) ? double(0.0) : w;
  return w > double(1.0) ? double(1.0) : w;
}

// The variance of a slot's channel mean from its sums and square sum in their values (fixed64's words times 2^-F and
// 2^-G, float32's floats), count >= 1: the three channels added in order, then CellVariance of the means.
HPSF_FN double SlotVariance(dvec3 sums, double square, double count) {
  HPSF_PRECISE double partial = sums[0] + sums[1];
  HPSF_PRECISE double brightness = partial + sums[2];
  HPSF_PRECISE double mean_brightness = brightness / count;
  HPSF_PRECISE double mean_square = square / count;
  return CellVariance(mean_brightness, mean_square);
}

// What the record's vertex receives: w average + (1 - w) own, per channel.
HPSF_FN dvec3 InterpolatedIncident(double w, dvec3 average, dvec3 own) {
  dvec3 incident;
  for (int c = 0; c < 3; ++c) {
    HPSF_PRECISE double cell = w * average[c];
    HPSF_PRECISE double path = (double(1.0) - w) * own[c];
    HPSF_PRECISE double sum = cell + path;
    incident[c] = sum;
  }
  return incident;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_CELL_INTERPOLATION_H
