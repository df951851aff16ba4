#include "verifier/metrics/image_metrics.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

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
    throw InputError(a.path + " and " + b.path + " cannot be compared: " + a.path + " is " + Shape(a) + ", " + b.path +
                     " is " + Shape(b));
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
  // Rows in fixed chunks on every core; the chunks' sums are added in chunk order, so no figure depends on the
  // number of threads. The percentile is selected without keeping every error: a histogram of the errors' top
  // 16 bits (a non-negative float's bits order as its value) finds the bucket that holds it, and a second pass
  // collects that bucket alone. Both give the k-th smallest whatever the threads did.
  const std::size_t width = std::size_t(a.width), per_pixel = colour.size();
  const auto error_of = [&](std::size_t p, std::size_t k, float* error) {
    const float va = a.At(p, colour[k]), vb = b.At(p, colour[k]);
    if (!std::isfinite(va) || !std::isfinite(vb)) return false;
    *error = float(std::abs(double(va) - double(vb)));
    return true;
  };
  const auto bucket_of = [](float error) { return std::bit_cast<std::uint32_t>(error) >> 16; };
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> histograms(
      [] { return std::vector<std::uint32_t>(1u << 16, 0u); });
  struct Part {
    double squared = 0.0, relative = 0.0, absolute = 0.0, peak = 1.0, max_abs = 0.0;
    std::size_t max_value = 0;  // pixel * colour count + colour index of the first maximum
    std::uint64_t values = 0, nonfinite_mismatches = 0, pixels_over = 0;
  };
  constexpr std::size_t kRowsPerChunk = 16;
  std::vector<Part> parts((std::size_t(a.height) + kRowsPerChunk - 1) / kRowsPerChunk);
  tbb::parallel_for(std::size_t(0), parts.size(), [&](std::size_t chunk) {
    Part& part = parts[chunk];
    std::vector<std::uint32_t>& histogram = histograms.local();
    const std::size_t end_pixel = std::min(std::size_t(a.height), (chunk + 1) * kRowsPerChunk) * width;
    for (std::size_t p = chunk * kRowsPerChunk * width; p < end_pixel; ++p) {
      double pixel_max = 0.0;
      for (std::size_t k = 0; k < per_pixel; ++k) {
        const float va = a.At(p, colour[k]), vb = b.At(p, colour[k]);
        if (!std::isfinite(va) || !std::isfinite(vb)) {
          part.nonfinite_mismatches += !SameNonFinite(va, vb);
          continue;
        }
        part.peak = std::max({part.peak, double(va), double(vb)});
        const double d = double(va) - double(vb);
        const double e = std::abs(d);
        part.squared += d * d;
        part.relative += d * d / (double(vb) * double(vb) + 0.01);
        part.absolute += e;
        ++part.values;
        ++histogram[bucket_of(float(e))];
        pixel_max = std::max(pixel_max, e);
        if (e > part.max_abs) {
          part.max_abs = e;
          part.max_value = p * per_pixel + k;
        }
      }
      part.pixels_over += pixel_max > options.pixel_threshold;
    }
  });
  double squared = 0.0, relative = 0.0, absolute = 0.0;
  std::uint64_t pixels_over = 0;
  std::size_t max_value = 0;
  for (const Part& part : parts) {
    squared += part.squared;
    relative += part.relative;
    absolute += part.absolute;
    pixels_over += part.pixels_over;
    m.values += part.values;
    m.nonfinite_mismatches += part.nonfinite_mismatches;
    m.peak = std::max(m.peak, part.peak);
    if (part.max_abs > m.max_abs) {  // strictly greater: the first maximum in pixel order stays
      m.max_abs = part.max_abs;
      max_value = part.max_value;
    }
  }
  m.max_x = int((max_value / per_pixel) % width);
  m.max_y = int((max_value / per_pixel) / width);
  m.max_channel = a.channels[colour[max_value % per_pixel]];
  const double n = std::max<double>(double(m.values), 1.0);
  m.mse = squared / n;
  m.rmse = std::sqrt(m.mse);
  m.relmse = relative / n;
  m.psnr = m.mse > 0.0 ? 20.0 * std::log10(m.peak / m.rmse) : std::numeric_limits<double>::infinity();
  m.mean_abs = absolute / n;
  m.fraction_over = double(pixels_over) / double(a.PixelCount());
  if (m.values > 0) {
    const double rank = std::ceil(options.percentile / 100.0 * double(m.values));
    std::uint64_t k = std::uint64_t(std::clamp(rank, 1.0, double(m.values))) - 1;  // from 0
    std::uint32_t bucket = 0;
    for (;; ++bucket) {
      std::uint64_t count = 0;
      for (const std::vector<std::uint32_t>& h : histograms) count += h[bucket];
      if (k < count) break;
      k -= count;
    }
    tbb::enumerable_thread_specific<std::vector<float>> found;
    tbb::parallel_for(std::size_t(0), parts.size(), [&](std::size_t chunk) {
      std::vector<float>& mine = found.local();
      const std::size_t end_pixel = std::min(std::size_t(a.height), (chunk + 1) * kRowsPerChunk) * width;
      for (std::size_t p = chunk * kRowsPerChunk * width; p < end_pixel; ++p) {
        for (std::size_t c = 0; c < per_pixel; ++c) {
          float e;
          if (error_of(p, c, &e) && bucket_of(e) == bucket) mine.push_back(e);
        }
      }
    });
    std::vector<float> in_bucket;
    for (const std::vector<float>& f : found) in_bucket.insert(in_bucket.end(), f.begin(), f.end());
    std::nth_element(in_bucket.begin(), in_bucket.begin() + std::ptrdiff_t(k), in_bucket.end());
    m.percentile = in_bucket[std::size_t(k)];
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
