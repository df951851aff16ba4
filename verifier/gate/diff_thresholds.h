// The vocabulary of an image verdict, shared by `hpsf diff`, the goldens' manifest and the gate: the metric a
// threshold is set on, the thresholds, the three verdicts and their exit codes. It needs no image: the rule that
// applies it to measured metrics is verifier/metrics/diff_verdict.h.
#ifndef HPSF_VERIFIER_GATE_DIFF_THRESHOLDS_H
#define HPSF_VERIFIER_GATE_DIFF_THRESHOLDS_H

#include <string>
#include <vector>

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

struct DiffThresholds {
  DiffMetric metric = DiffMetric::kMaxAbs;
  double warn = 0.0;  // any difference at all warns: exactness is what hpsf promises
  double fail = 1e-6;
};

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_DIFF_THRESHOLDS_H
