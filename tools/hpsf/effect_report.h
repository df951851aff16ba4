// The effect plan in a command's report (core/effect_plan.h): for each effect, whether it ran, on how many frames,
// whether it was forced, and why.
#ifndef HPSF_TOOLS_HPSF_EFFECT_REPORT_H
#define HPSF_TOOLS_HPSF_EFFECT_REPORT_H

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/effect_plan.h"
#include "tracer/scene.h"

namespace hpsf {

SceneFacts FactsOf(const Scene& scene);

// [{"effect", "ran", "frames_run", "asked", "forced", "reason"}, ...] in the plan's order.
nlohmann::json EffectsJson(const std::vector<EffectDecision>& plan);

// One line for a terminal: "effects: ran temporal on 3 of 4 frames; skipped eviction: ..."; empty when no effect
// was asked for or forced (a single frame's one build of its scene aside).
std::string EffectsLine(const std::vector<EffectDecision>& plan, std::uint32_t frames);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_EFFECT_REPORT_H
