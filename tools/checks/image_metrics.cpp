#include "tools/checks/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace hpsf {
namespace {

std::string Shape(const ChannelImage& image) {
  std::string channels;
  for (const std::string& c : image.channels) channels += (channels.empty() ? "" : ",") + c;
  return std::to_string(image.width) + "x" + std::to_string(image.height) + " [" + channels + "]";
}

bool SameNonFinite(float a, float b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

// JSON has no infinity: an unbounded PSNR is written as null.
nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

void CheckComparable(const ChannelImage& a, const ChannelImage& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
    throw InputError(a.path + " and " + b.path + " cannot be compared: " + a.path + " is " + Shape(a) + ", " +
                     b.path + " is " + Shape(b));
  }
  if (a.PixelCount() == 0) throw InputError(a.path + ": the image has no pixels");
}

ImageMetrics ComputeMetrics(const ChannelImage& a, const ChannelImage& b, const MetricOptions& options) {
  CheckComparable(a, b);
  std::vector<std::size_t> colour;
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    if (IsColorChannel(a.channels[c])) colour.push_back(c);
  }
  if (colour.empty()) throw InputError(a.path + ": the image has no colour channels to compare");
  ImageMetrics m;
  m.percentile_rank = options.percentile;
  m.pixel_threshold = options.pixel_threshold;
  std::vector<double> errors;
  errors.reserve(a.PixelCount() * colour.size());
  double squared = 0.0, relative = 0.0, absolute = 0.0;
  std::uint64_t pixels_over = 0;
  for (std::size_t p = 0; p < a.PixelCount(); ++p) {
    double pixel_max = 0.0;
    for (std::size_t c : colour) {
      const float va = a.At(p, c), vb = b.At(p, c);
      if (!std::isfinite(va) || !std::isfinite(vb)) {
        if (!SameNonFinite(va, vb)) ++m.nonfinite_mismatches;
        continue;
      }
      m.peak = std::max({m.peak, double(va), double(vb)});
      const double d = double(va) - double(vb);
      const double e = std::abs(d);
      squared += d * d;
      relative += d * d / (double(vb) * double(vb) + 0.01);
      absolute += e;
      errors.push_back(e);
      pixel_max = std::max(pixel_max, e);
      if (e > m.max_abs) {
        m.max_abs = e;
        m.max_x = int(p % std::size_t(a.width));
        m.max_y = int(p / std::size_t(a.width));
        m.max_channel = a.channels[c];
      }
    }
    pixels_over += pixel_max > options.pixel_threshold;
  }
  m.values = errors.size();
  if (m.max_channel.empty()) m.max_channel = a.channels[colour.front()];
  const double n = std::max<double>(double(errors.size()), 1.0);
  m.mse = squared / n;
  m.rmse = std::sqrt(m.mse);
  m.relmse = relative / n;
  m.psnr = m.mse > 0.0 ? 20.0 * std::log10(m.peak / m.rmse) : std::numeric_limits<double>::infinity();
  m.mean_abs = absolute / n;
  m.fraction_over = double(pixels_over) / double(a.PixelCount());
  if (!errors.empty()) {
    const double rank = std::ceil(options.percentile / 100.0 * double(errors.size()));
    const std::size_t k = std::size_t(std::clamp(rank, 1.0, double(errors.size()))) - 1;
    std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(k), errors.end());
    m.percentile = errors[k];
  }
  return m;
}

std::string ImageMetrics::ToString() const {
  std::ostringstream s;
  s.precision(6);
  s << "[ ImageMetrics values: " << values << " mse: " << mse << " rmse: " << rmse << " relmse: " << relmse
    << " psnr: " << psnr << " mean_abs: " << mean_abs << " max_abs: " << max_abs << " at (" << max_x << ", " << max_y
    << ", " << max_channel << ") p" << percentile_rank << ": " << percentile << " fraction_over(" << pixel_threshold
    << "): " << fraction_over << " nonfinite_mismatches: " << nonfinite_mismatches << " ]";
  return s.str();
}

nlohmann::json ToJson(const ImageMetrics& m) {
  return {{"values", m.values},
          {"mse", m.mse},
          {"rmse", m.rmse},
          {"relmse", m.relmse},
          {"psnr", Number(m.psnr)},
          {"psnr_peak", m.peak},
          {"mean_abs", m.mean_abs},
          {"max_abs", m.max_abs},
          {"max_at", {{"x", m.max_x}, {"y", m.max_y}, {"channel", m.max_channel}}},
          {"percentile", {{"rank", m.percentile_rank}, {"value", m.percentile}}},
          {"fraction_over", {{"threshold", m.pixel_threshold}, {"value", m.fraction_over}}},
          {"nonfinite_mismatches", m.nonfinite_mismatches}};
}

}  // namespace hpsf
