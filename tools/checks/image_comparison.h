// One comparison of a test image A with a reference B, as `hpsf diff` and `hpsf golden check` make it: the
// metrics, SSIM, the verdict under the written rule (tools/checks/diff_verdict.h), the metadata that differs,
// and the time each part took.
#ifndef HPSF_TOOLS_CHECKS_IMAGE_COMPARISON_H
#define HPSF_TOOLS_CHECKS_IMAGE_COMPARISON_H

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/checks/channel_image.h"
#include "tools/checks/diff_verdict.h"
#include "tools/checks/image_metrics.h"
#include "tools/checks/metadata_diff.h"

namespace hpsf {

struct ComparisonOptions {
  DiffThresholds thresholds;
  MetricOptions metrics;
};

struct ImageComparison {
  ImageMetrics metrics;
  double ssim = 1.0;
  DiffThresholds thresholds;
  double value = 0.0;  // the judged metric's value
  DiffVerdict verdict = DiffVerdict::kPass;
  std::vector<MetadataDifference> metadata;
  double metrics_seconds = 0.0, ssim_seconds = 0.0;
  // One line: the verdict and why, e.g. "WARN: max 0.5 at (3, 4, R) is above --warn 0, not above --fail 1".
  std::string Explanation() const;
};

// Throws InputError (naming both files) when the images cannot be compared.
ImageComparison CompareImages(const ChannelImage& a, const ChannelImage& b, const ComparisonOptions& options);

nlohmann::json ToJson(const ImageComparison& comparison);

}  // namespace hpsf

#endif  // HPSF_TOOLS_CHECKS_IMAGE_COMPARISON_H
