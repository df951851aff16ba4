// The verdict of `hpsf diff`, one written rule:
//   FAIL (exit 2) when the chosen metric is worse than --fail, or a value is non-finite in one image and not
//   the same non-finite value in the other;
//   otherwise WARN (exit 1) when the metric is worse than --warn;
//   otherwise PASS (exit 0).
// "Worse" is "greater", except for PSNR and SSIM, where it is "smaller". So a maximum error above --warn and
// below --fail is a WARN: idiff reports PASS there, hpsf does not hide it.
#ifndef HPSF_VERIFIER_METRICS_DIFF_VERDICT_H
#define HPSF_VERIFIER_METRICS_DIFF_VERDICT_H

#include "verifier/gate/diff_thresholds.h"
#include "verifier/metrics/image_metrics.h"

namespace hpsf {

// The metric's value; ssim is passed in (computed only when asked for, see verifier/metrics/ssim.h).
double MetricValue(const ImageMetrics& metrics, DiffMetric metric, double ssim);

DiffVerdict Judge(const ImageMetrics& metrics, double ssim, const DiffThresholds& thresholds);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_DIFF_VERDICT_H
