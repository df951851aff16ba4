// The gate's statistics family (gate_families.h): scene x config x seed, each case one `hpsf stats`, which holds
// the batch's load, probe lengths, probe failures, aliases and jitter to their theory. A rate above its theory is a
// warning (exit 1), not a failure: the theory is a bound, and a scene may cluster more than uniform hashing does.
#include "verifier/gate/gate_families.h"

namespace hpsf::gate {

using nlohmann::json;

void ExpandStatistics(const json& s, const std::string& folder, const GateError& error, Gate& gate) {
  const std::string at = "/statistics";
  if (!s.is_object()) error.At(at, "expected an object");
  RequireKeys(s, {"scenes", "size", "spp", "seeds", "configs"}, at, error);
  const std::vector<SceneEntry> scenes = Scenes(s, at, folder, error);
  const std::vector<std::string> trace = TraceArguments(s, at, error);
  const std::vector<std::uint32_t> seeds = Seeds(s, at, error);
  const std::vector<Named> configs = NamedOptions(s, "configs", {{"default", json::object()}}, at, error);
  for (const SceneEntry& scene : scenes) {
    for (const Named& config : configs) {
      for (const std::uint32_t seed : seeds) {
        GateCase gc;
        gc.family = "statistics";
        gc.id = "statistics/" + scene.name + "/" + config.name + "/seed" + std::to_string(seed);
        gc.where = scene.pointer + ", " + config.pointer;
        gc.arguments = {"stats", scene.input};
        if (!scene.recorded) gc.arguments.insert(gc.arguments.end(), trace.begin(), trace.end());
        gc.arguments.insert(gc.arguments.end(), {"--seed", std::to_string(seed)});
        const std::vector<std::string> a = Arguments(config, folder, {}, error);
        gc.arguments.insert(gc.arguments.end(), a.begin(), a.end());
        gate.cases.push_back(std::move(gc));
      }
    }
  }
}

}  // namespace hpsf::gate
