// The verdict of `hpsf diff`, one written rule:
//   FAIL (exit 2) when the chosen metric is worse than --fail, or a value is non-finite in one image and not
//   the same non-finite value in the other;
//   otherwise WARN (exit 1) when the metric is worse than --warn;
//   otherwise PASS (exit 0).
// "Worse" is "greater", except for PSNR and SSIM, where it is "smaller". So a maximum error above --warn and
// below --fail is a WARN: idiff reports PASS there, hpsf does not hide it.
#ifndef HPSF_TOOLS_CHECKS_DIFF_VERDICT_H
#define HPSF_TOOLS_CHECKS_DIFF_VERDICT_H

#include <string>
#include <vector>

#include "tools/checks/image_metrics.h"

namespace hpsf {

enum class DiffMetric { kMse, kRmse, kRelMse, kPsnr, kMeanAbs, kMaxAbs, kPercentile, kFractionOver, kSsim };
enum class DiffVerdict { kPass, kWarn, kFail };

// Names as the command line takes them: mse, rmse, relmse, psnr, mean, max, percentile, fraction, ssim.
DiffMetric ParseDiffMetric(const std::string& name);  // ConfigError naming --metric
std::string ToString(DiffMetric metric);
std::vector<std::string> DiffMetricNames();
bool HigherIsBetter(DiffMetric metric);
std::string ToString(DiffVerdict verdict);  // PASS, WARN, FAIL
int ExitCode(DiffVerdict verdict);          // 0, 1, 2

// The metric's value; ssim is passed in (computed only when asked for, see tools/checks/ssim.h).
double MetricValue(const ImageMetrics& metrics, DiffMetric metric, double ssim);

struct DiffThresholds {
  DiffMetric metric = DiffMetric::kMaxAbs;
  double warn = 0.0;  // any difference at all warns: exactness is what hpsf promises
  double fail = 1e-6;
};

DiffVerdict Judge(const ImageMetrics& metrics, double ssim, const DiffThresholds& thresholds);

}  // namespace hpsf

#endif  // HPSF_TOOLS_CHECKS_DIFF_VERDICT_H
