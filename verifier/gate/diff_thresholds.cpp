#include "verifier/gate/diff_thresholds.h"

#include <array>
#include <utility>

#include "core/error.h"

namespace hpsf {
namespace {

constexpr std::array<std::pair<DiffMetric, const char*>, 9> kNames = {{{DiffMetric::kMse, "mse"},
                                                                       {DiffMetric::kRmse, "rmse"},
                                                                       {DiffMetric::kRelMse, "relmse"},
                                                                       {DiffMetric::kPsnr, "psnr"},
                                                                       {DiffMetric::kMeanAbs, "mean"},
                                                                       {DiffMetric::kMaxAbs, "max"},
                                                                       {DiffMetric::kPercentile, "percentile"},
                                                                       {DiffMetric::kFractionOver, "fraction"},
                                                                       {DiffMetric::kSsim, "ssim"}}};

}  // namespace

DiffMetric ParseDiffMetric(const std::string& name) {
  for (const auto& [metric, text] : kNames) {
    if (name == text) return metric;
  }
  std::string known;
  for (const std::string& n : DiffMetricNames()) known += (known.empty() ? "" : ", ") + n;
  throw ConfigError("--metric", "unknown metric '" + name + "' (one of " + known + ")");
}

std::string ToString(DiffMetric metric) {
  for (const auto& [m, text] : kNames) {
    if (m == metric) return text;
  }
  return "?";
}

std::vector<std::string> DiffMetricNames() {
  std::vector<std::string> names;
  for (const auto& entry : kNames) names.emplace_back(entry.second);
  return names;
}

bool HigherIsBetter(DiffMetric metric) { return metric == DiffMetric::kPsnr || metric == DiffMetric::kSsim; }

std::string ToString(DiffVerdict verdict) {
  switch (verdict) {
    case DiffVerdict::kPass:
      return "PASS";
    case DiffVerdict::kWarn:
      return "WARN";
    case DiffVerdict::kFail:
      return "FAIL";
  }
  return "?";
}

int ExitCode(DiffVerdict verdict) {
  switch (verdict) {
    case DiffVerdict::kPass:
      return kExitOk;
    case DiffVerdict::kWarn:
      return kExitWarn;
    case DiffVerdict::kFail:
      return kExitCheckFailed;
  }
  return kExitCheckFailed;
}

}  // namespace hpsf
