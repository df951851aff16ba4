// Variance-aware path survival (Schipek §4.1.1, eqs. 4.1 and 4.2): before a sample's path is traced past its primary
// vertex, it survives with a probability p(v) of the variance v of that vertex's cell in the table the frame before
// left. A culled path is not traced further: its record enters its cell with a contribution of 0; a surviving one
// carries its contribution divided by p. That is a Horvitz-Thompson estimate of each sample's contribution, so the
// cell's average stays unbiased (E[c'] = p c / p = E[c]), its variance rises to E[c^2] / p - E[c]^2, and the cell's
// count keeps counting every sample.
//
// The decision reads the table before the frame only (never the one the frame accumulates: D10's cousin), through
// PreviousTableView (core/previous_table_view.h), so that every backend is handed the same records: `hpsf crosscheck`
// decides by the reference's exact map, `hpsf render` by the rendering backend's own table. A cell that is not in that
// table, or holds fewer than two samples, says nothing of its variance: p = 1.
#ifndef HPSF_CORE_SURVIVAL_H
#define HPSF_CORE_SURVIVAL_H

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

namespace hpsf {

enum class SurvivalFunction {
  kOff,
  kLinear,  // eq. 4.1: clamp((v - v0) / (v1 - v0), 0, 1)
  kSmooth,  // eq. 4.2: Schipek's smoothstep of the linear ramp
};

struct SurvivalParams {
  SurvivalFunction function = SurvivalFunction::kOff;
  double v0 = 0.0;  // below: the function's least probability
  double v1 = 1.0;  // above: 1
  // The least probability of survival, > 0: eqs. 4.1 and 4.2 reach 0, where the reweighting would divide by it and a
  // cell would starve (Schipek: "no paths get starved").
  double floor = 0.0625;
  // false only in tests: survivors keep their contribution (the broken variant "survival without the reweighting",
  // which darkens a cell's average by its survival probability).
  bool reweight = true;
  bool enabled() const { return function != SurvivalFunction::kOff; }
  std::string ToString() const;  // "off", "linear:V0:V1:FLOOR" or "smooth:V0:V1:FLOOR"
  bool operator==(const SurvivalParams&) const = default;
};

// "off", "linear:V0:V1[:FLOOR]" or "smooth:V0:V1[:FLOOR]" with 0 <= V0 < V1 finite and FLOOR in (0, 1]; a ConfigError
// naming --survival otherwise.
SurvivalParams ParseSurvival(const std::string& text);

// p(v) of the params' function, at least their floor; in double, from exact or correctly rounded steps only.
double SurvivalProbability(const SurvivalParams& params, double variance);

// The draw u in [0, 1) that decides whether the sample (pixel, sample) of a trace of `seed` survives its primary vertex
// at `bounce` in `frame`: the counter RNG's dimension 8 at that vertex, one the tracer draws for nothing else, so the
// surviving paths are the same paths as without survival. It survives where u < p.
float SurvivalDraw(std::uint32_t seed, std::uint32_t frame, std::uint32_t pixel, std::uint32_t sample,
                   std::uint32_t bounce);

// What a sample whose path carries `light` adds to its cell after the decision: 0 where it is culled (u >= p); where
// it survives, light / p in double rounded to float once (light itself without the reweighting).
glm::vec3 SurvivingContribution(const SurvivalParams& params, const glm::dvec3& light, float u, double p);

}  // namespace hpsf

#endif  // HPSF_CORE_SURVIVAL_H
