#include "tools/hpsf/cell_variance_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace hpsf {
namespace {

float Percentile(std::vector<float> values, double q) {
  const std::size_t k = std::min(values.size() - 1, std::size_t(std::ceil(q * double(values.size()))) - 1);
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
  return values[k];
}

std::string Number(const char* format, double value) {
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace

Rgb8Image RenderCellVarianceMap(std::span<const float> variance, int width, int height) {
  std::vector<float> positive;
  for (const float v : variance) {
    if (v > 0.0f && std::isfinite(v)) positive.push_back(v);
  }
  // One decade at least, so that a table of one variance still shows it mid-scale.
  float low = positive.empty() ? 1.0f : Percentile(positive, 0.01);
  float high = positive.empty() ? 10.0f : Percentile(positive, 0.99);
  high = std::max(high, low * 10.0f);
  const double log_low = std::log10(double(low)), span = std::log10(double(high)) - log_low;
  std::vector<float> unit(variance.size(), 0.0f);
  for (std::size_t p = 0; p < variance.size(); ++p) {
    const float v = variance[p];
    if (!(v > 0.0f)) continue;  // no cell, or a variance of 0: black
    const double t = std::isfinite(v) ? (std::log10(double(v)) - log_low) / span : 1.0;
    unit[p] = float(std::clamp(t, 0.02, 1.0));  // the lowest variance still distinguishable from no cell
  }
  return RenderColourMap(unit, width, height,
                         {Number("<= %.2g", low), "variance per cell, log", Number(">= %.2g", high), 0.5});
}

std::string CellVarianceMapPath(const std::string& output) {
  std::filesystem::path path(output);
  path.replace_extension("cell-variance.png");
  return path.string();
}

}  // namespace hpsf
