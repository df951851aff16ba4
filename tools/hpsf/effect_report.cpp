#include "tools/hpsf/effect_report.h"

namespace hpsf {

SceneFacts FactsOf(const Scene& scene) { return SceneFacts{true, !scene.animation.Static()}; }

nlohmann::json EffectsJson(const std::vector<EffectDecision>& plan) {
  nlohmann::json effects = nlohmann::json::array();
  for (const EffectDecision& d : plan) {
    effects.push_back({{"effect", EffectName(d.effect)},
                       {"ran", d.frames_run > 0},
                       {"frames_run", d.frames_run},
                       {"asked", d.asked},
                       {"forced", d.forced},
                       {"reason", d.reason}});
  }
  return effects;
}

std::string EffectsLine(const std::vector<EffectDecision>& plan, std::uint32_t frames) {
  std::string ran, skipped;
  for (const EffectDecision& d : plan) {
    if (!d.asked && !d.forced) continue;
    if (d.effect == Effect::kAnimation && frames == 1 && !d.forced) continue;  // one frame is one build either way
    const std::string name = EffectName(d.effect) + (d.forced ? " (forced)" : "");
    if (d.frames_run > 0) {
      ran += (ran.empty() ? "" : ", ") + name + " on " + std::to_string(d.frames_run) + " of " +
             std::to_string(frames) + (frames == 1 ? " frame" : " frames");
    } else {
      skipped += (skipped.empty() ? "" : "; ") + name + ": " + d.reason;
    }
  }
  if (ran.empty() && skipped.empty()) return "";
  return "effects: ran " + (ran.empty() ? std::string("none") : ran) +
         (skipped.empty() ? std::string() : "; skipped " + skipped);
}

}  // namespace hpsf
