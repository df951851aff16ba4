#include "verifier/metrics/image_comparison.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "verifier/metrics/ssim.h"

namespace hpsf {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string Shown(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

}  // namespace

ImageComparison CompareImages(const ChannelImage& a, const ChannelImage& b, const ComparisonOptions& options) {
  ImageComparison c;
  c.thresholds = options.thresholds;
  auto start = std::chrono::steady_clock::now();
  c.metrics = ComputeMetrics(a, b, options.metrics);
  c.metrics_seconds = SecondsSince(start);
  if (options.ssim || c.thresholds.metric == DiffMetric::kSsim) {
    start = std::chrono::steady_clock::now();
    c.ssim = SrgbSsim(a, b);
    c.ssim_seconds = SecondsSince(start);
  }
  const double ssim = c.ssim.value_or(std::numeric_limits<double>::quiet_NaN());
  c.value = MetricValue(c.metrics, c.thresholds.metric, ssim);
  c.verdict = Judge(c.metrics, ssim, c.thresholds);
  c.metadata = DiffMetadata(a.metadata, b.metadata);
  return c;
}

std::string ImageComparison::Explanation() const {
  const std::string verdict_text = ToString(verdict);
  if (judged_by) return verdict_text + ": " + *judged_by;
  if (metrics.nonfinite_mismatches > 0) {
    return verdict_text + ": " + std::to_string(metrics.nonfinite_mismatches) +
           " values are not finite in one image and differ in the other";
  }
  const bool higher = HigherIsBetter(thresholds.metric);
  const std::string name = ToString(thresholds.metric), above = higher ? "below" : "above";
  std::string value_text = name + " " + Shown(value);
  if (thresholds.metric == DiffMetric::kMaxAbs && metrics.max_abs > 0.0) {
    value_text += " at (" + std::to_string(metrics.max_x) + ", " + std::to_string(metrics.max_y) + ", " +
                  metrics.max_channel + ")";
  }
  switch (verdict) {
    case DiffVerdict::kFail:
      return verdict_text + ": " + value_text + " is " + above + " --fail " + Shown(thresholds.fail);
    case DiffVerdict::kWarn:
      return verdict_text + ": " + value_text + " is " + above + " --warn " + Shown(thresholds.warn) + ", not " +
             above + " --fail " + Shown(thresholds.fail);
    case DiffVerdict::kPass:
      return verdict_text + ": " + value_text + " is not " + above + " --warn " + Shown(thresholds.warn);
  }
  return verdict_text;
}

nlohmann::json ToJson(const ImageComparison& c) {
  nlohmann::json j;
  j["metrics"] = ToJson(c.metrics);
  j["metrics"]["ssim"] = c.ssim ? nlohmann::json(*c.ssim) : nlohmann::json(nullptr);
  j["rule"] = {{"metric", ToString(c.thresholds.metric)},
               {"warn", c.thresholds.warn},
               {"fail", c.thresholds.fail},
               {"worse_is", HigherIsBetter(c.thresholds.metric) ? "smaller" : "greater"}};
  j["value"] = std::isfinite(c.value) ? nlohmann::json(c.value) : nlohmann::json(nullptr);
  j["verdict"] = ToString(c.verdict);
  j["explanation"] = c.Explanation();
  j["metadata_differences"] = ToJson(c.metadata);
  j["timings"] = {{"metrics_s", c.metrics_seconds}, {"ssim_s", c.ssim_seconds}};
  return j;
}

}  // namespace hpsf
