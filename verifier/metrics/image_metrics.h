// The plain metrics of `hpsf diff`: how far a test image A is from a reference B, over their colour channels.
// With d = a - b per value (pixel and channel), n values in all:
//   MSE = sum d^2 / n;  RMSE = sqrt(MSE);  relMSE = sum d^2 / (b^2 + 0.01) / n (the denoising literature's);
//   PSNR = 20 log10(peak / RMSE) with peak the largest value in A or B but at least 1, as OpenImageIO's idiff
//   takes it (+inf when equal), so the two agree on HDR renders;
//   mean and maximum |d| and where the maximum is (the first in pixel order on a tie);
//   the p-th percentile of |d| (nearest rank, rounded to float); the fraction of pixels whose largest |d| exceeds
//   a threshold.
// A value that is not finite in A or B is not a number to subtract: it counts as equal when A and B hold the
// same one (both NaN, or the same infinity) and as a mismatch otherwise, and enters no other metric. SSIM is
// computed elsewhere (verifier/metrics/ssim.h).
#ifndef HPSF_VERIFIER_METRICS_IMAGE_METRICS_H
#define HPSF_VERIFIER_METRICS_IMAGE_METRICS_H

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "verifier/metrics/channel_image.h"

namespace hpsf {

struct MetricOptions {
  double percentile = 99.0;       // in (0, 100]
  double pixel_threshold = 1e-3;  // for the fraction of pixels over it
};

struct ImageMetrics {
  std::uint64_t values = 0;  // pixels x colour channels compared
  std::uint64_t nonfinite_mismatches = 0;
  double mse = 0.0, rmse = 0.0, relmse = 0.0, psnr = 0.0;
  double mean_abs = 0.0, max_abs = 0.0;
  double peak = 1.0;  // PSNR's
  int max_x = 0, max_y = 0;
  std::string max_channel;
  double percentile = 0.0;  // the value of the percentile below
  double percentile_rank = 99.0;
  double fraction_over = 0.0;  // of pixels
  double pixel_threshold = 1e-3;
  std::string ToString() const;
};

// Throws InputError naming both files when A and B differ in size or channels.
void CheckComparable(const ChannelImage& a, const ChannelImage& b);

ImageMetrics ComputeMetrics(const ChannelImage& a, const ChannelImage& b, const MetricOptions& options = {});

nlohmann::json ToJson(const ImageMetrics& m);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_IMAGE_METRICS_H
