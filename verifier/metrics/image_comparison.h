// One comparison of a test image A with a reference B, as `hpsf diff` and `hpsf golden check` make it: the
// metrics, SSIM, the verdict under the written rule (verifier/metrics/diff_verdict.h), the metadata that differs,
// and the time each part took.
#ifndef HPSF_VERIFIER_METRICS_IMAGE_COMPARISON_H
#define HPSF_VERIFIER_METRICS_IMAGE_COMPARISON_H

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "verifier/metrics/channel_image.h"
#include "verifier/metrics/diff_verdict.h"
#include "verifier/metrics/image_metrics.h"
#include "verifier/metrics/metadata_diff.h"

namespace hpsf {

struct ComparisonOptions {
  DiffThresholds thresholds;
  MetricOptions metrics;
  bool ssim = true;  // SSIM costs about 1.3 us a pixel (2.7 s at 1080p, against 26 ms for every other metric)
};

struct ImageComparison {
  ImageMetrics metrics;
  std::optional<double> ssim;  // when computed (always when it is the judged metric)
  DiffThresholds thresholds;
  double value = 0.0;  // the judged metric's value
  DiffVerdict verdict = DiffVerdict::kPass;
  std::vector<MetadataDifference> metadata;
  double metrics_seconds = 0.0, ssim_seconds = 0.0;
  // Set when another test gave the verdict (hpsf diff --statistical): why it did.
  std::optional<std::string> judged_by;
  // One line: the verdict and why, e.g. "WARN: max 0.5 at (3, 4, R) is above --warn 0, not above --fail 1".
  std::string Explanation() const;
};

// Throws InputError (naming both files) when the images cannot be compared.
ImageComparison CompareImages(const ChannelImage& a, const ChannelImage& b, const ComparisonOptions& options);

nlohmann::json ToJson(const ImageComparison& comparison);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_IMAGE_COMPARISON_H
