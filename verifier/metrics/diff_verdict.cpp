#include "verifier/metrics/diff_verdict.h"

namespace hpsf {

double MetricValue(const ImageMetrics& m, DiffMetric metric, double ssim) {
  switch (metric) {
    case DiffMetric::kMse:
      return m.mse;
    case DiffMetric::kRmse:
      return m.rmse;
    case DiffMetric::kRelMse:
      return m.relmse;
    case DiffMetric::kPsnr:
      return m.psnr;
    case DiffMetric::kMeanAbs:
      return m.mean_abs;
    case DiffMetric::kMaxAbs:
      return m.max_abs;
    case DiffMetric::kPercentile:
      return m.percentile;
    case DiffMetric::kFractionOver:
      return m.fraction_over;
    case DiffMetric::kSsim:
      return ssim;
  }
  return 0.0;
}

DiffVerdict Judge(const ImageMetrics& metrics, double ssim, const DiffThresholds& t) {
  if (metrics.nonfinite_mismatches > 0) return DiffVerdict::kFail;
  const double value = MetricValue(metrics, t.metric, ssim);
  auto worse = [&](double threshold) { return HigherIsBetter(t.metric) ? value < threshold : value > threshold; };
  if (worse(t.fail)) return DiffVerdict::kFail;
  if (worse(t.warn)) return DiffVerdict::kWarn;
  return DiffVerdict::kPass;
}

}  // namespace hpsf
