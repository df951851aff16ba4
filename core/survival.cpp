#include "core/survival.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/number_list.h"
#include "core/shared/rng.h"

namespace hpsf {
namespace {

double Clamp01(double x) { return std::clamp(x, 0.0, 1.0); }

}  // namespace

std::string SurvivalParams::ToString() const {
  if (function == SurvivalFunction::kOff) return "off";
  return std::string(function == SurvivalFunction::kLinear ? "linear:" : "smooth:") + FormatDouble(v0) + ":" +
         FormatDouble(v1) + ":" + FormatDouble(floor);
}

SurvivalParams ParseSurvival(const std::string& text) {
  if (text == "off") return {};
  const std::string usage = "expected off, linear:V0:V1[:FLOOR] or smooth:V0:V1[:FLOOR]";
  SurvivalParams params;
  std::size_t from = 0;
  if (text.rfind("linear:", 0) == 0) {
    params.function = SurvivalFunction::kLinear;
    from = 7;
  } else if (text.rfind("smooth:", 0) == 0) {
    params.function = SurvivalFunction::kSmooth;
    from = 7;
  } else {
    throw ConfigError("--survival", usage + "; got '" + text + "'");
  }
  const std::optional<std::vector<double>> values = ParseNumberList(text, from);
  if (!values || values->size() < 2 || values->size() > 3)
    throw ConfigError("--survival", usage + "; got '" + text + "'");
  params.v0 = (*values)[0];
  params.v1 = (*values)[1];
  if (values->size() == 3) params.floor = (*values)[2];
  if (!(std::isfinite(params.v0) && std::isfinite(params.v1) && params.v0 >= 0.0 && params.v0 < params.v1)) {
    throw ConfigError("--survival", "the variance thresholds need 0 <= V0 < V1, both finite; got '" + text + "'");
  }
  // Eq. 4.2's upper edge, 1 - (v1 - v0) / 8, must stay above its lower edge 0.
  if (params.function == SurvivalFunction::kSmooth && !(params.v1 - params.v0 < 8.0)) {
    throw ConfigError("--survival",
                      "smooth needs V1 - V0 below 8 (eq. 4.2's ramp ends at 1 - (V1 - V0) / 8); got '" + text + "'");
  }
  if (!(params.floor > 0.0 && params.floor <= 1.0)) {
    throw ConfigError("--survival", "FLOOR, the least probability of survival, must lie in (0, 1]; got '" + text + "'");
  }
  return params;
}

double SurvivalProbability(const SurvivalParams& params, double variance) {
  double p = 1.0;
  if (params.function == SurvivalFunction::kLinear) {
    p = Clamp01((variance - params.v0) / (params.v1 - params.v0));
  } else if (params.function == SurvivalFunction::kSmooth) {
    const double width = params.v1 - params.v0;
    const double edge = 1.0 - width / 8.0;
    const double x = (variance - (params.v1 + params.v0) * 0.5) / (width * 5.0) + edge * 0.5;
    const double t = Clamp01(x / edge);
    p = t * t * (3.0 - 2.0 * t);
  }
  return std::max(p, params.floor);
}

float SurvivalDraw(std::uint32_t seed, std::uint32_t frame, std::uint32_t pixel, std::uint32_t sample,
                   std::uint32_t bounce) {
  constexpr std::uint32_t kSurvivalDimension = 8;  // the tracer's dimensions 0 to 7: pixel, lights, bounce, roulette
  return shared::RandomFloatFromPrefix(shared::RngPrefix(shared::RngCounter{seed, frame, pixel, sample, bounce}),
                                       kSurvivalDimension);
}

glm::vec3 SurvivingContribution(const SurvivalParams& params, const glm::dvec3& light, float u, double p) {
  if (double(u) >= p) return glm::vec3(0.0f);
  return glm::vec3(params.reweight ? light / p : light);
}

}  // namespace hpsf
