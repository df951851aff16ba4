// The gate's crosscheck family (gate_families.h): scene x config x backend x sequence x seed, each case one
// `hpsf crosscheck` of a backend beside the reference.
#include <algorithm>
#include <map>
#include <set>

#include "core/backend_registry.h"
#include "verifier/gate/gate_families.h"

namespace hpsf::gate {

using nlohmann::json;

void ExpandCrosscheck(const json& c, const std::string& folder, const GateError& error, Gate& gate) {
  const std::string at = "/crosscheck";
  if (!c.is_object()) error.At(at, "expected an object");
  RequireKeys(c, {"scenes", "size", "spp", "seeds", "configs", "backends", "sequences"}, at, error);
  const std::vector<SceneEntry> scenes = Scenes(c, at, folder, error);
  const std::vector<std::string> trace = TraceArguments(c, at, error);
  const std::vector<std::uint32_t> seeds = Seeds(c, at, error);
  const std::vector<Named> configs = NamedOptions(c, "configs", {{"default", json::object()}}, at, error);
  if (!c.contains("backends")) error.At(at + "/backends", "expected an object of named backends");
  const std::vector<Named> backends = NamedOptions(c, "backends", json(), at, error);
  const std::vector<Named> sequences = NamedOptions(c, "sequences", {{"one-frame", json::object()}}, at, error);
  for (const Named& b : backends) {
    const auto hashed = RegisteredBackends();
    const bool known = b.options.contains("backend") && b.options["backend"].is_string() &&
                       std::any_of(hashed.begin(), hashed.end(), [&](const BackendInfo& info) {
                         return info.hashed && b.options["backend"] == info.name;
                       });
    if (!known) {
      error.At(b.pointer + "/backend", "expected the backend checked beside the reference: " + BackendNames(true));
    }
  }
  // A sequence's "gate-backends" and "gate-configs": the family's backend and config sets it runs on (names,
  // comma-separated), where a pass is not built on every backend or cannot run with every config; the others skip
  // it. Not command-line options.
  std::map<std::string, std::set<std::string>> runs_on_backends, runs_on_configs;
  const auto limit = [&](const std::string& key, const std::vector<Named>& sets, const std::string& what,
                         std::map<std::string, std::set<std::string>>& runs_on) {
    for (const Named& sequence : sequences) {
      if (!sequence.options.contains(key)) continue;
      const json& value = sequence.options[key];
      const std::string pointer = sequence.pointer + "/" + key;
      if (!value.is_string())
        error.At(pointer, "expected a comma-separated string of this family's " + what + " names");
      std::set<std::string>& names = runs_on[sequence.name];
      std::string list = value.get<std::string>() + ",";
      for (std::size_t start = 0, comma; (comma = list.find(',', start)) != std::string::npos; start = comma + 1) {
        const std::string name = list.substr(start, comma - start);
        if (std::none_of(sets.begin(), sets.end(), [&](const Named& set) { return set.name == name; })) {
          error.At(pointer, "'" + name + "' names none of this family's " + what + "s");
        }
        names.insert(name);
      }
    }
  };
  limit("gate-backends", backends, "backend", runs_on_backends);
  limit("gate-configs", configs, "config", runs_on_configs);
  const auto skips = [](const std::map<std::string, std::set<std::string>>& runs_on, const Named& sequence,
                        const Named& set) {
    const auto only = runs_on.find(sequence.name);
    return only != runs_on.end() && !only->second.contains(set.name);
  };
  for (const SceneEntry& scene : scenes) {
    // A recorded sequence holds its own frames.
    std::set<std::string> skipped = scene.recorded ? std::set<std::string>{"frames", "frame"} : std::set<std::string>{};
    skipped.insert({"gate-backends", "gate-configs"});
    for (const Named& config : configs) {
      for (const Named& backend : backends) {
        for (const Named& sequence : sequences) {
          if (skips(runs_on_backends, sequence, backend) || skips(runs_on_configs, sequence, config)) continue;
          for (const std::uint32_t seed : seeds) {
            GateCase gc;
            gc.family = "crosscheck";
            gc.id = "crosscheck/" + scene.name + "/" + config.name + "/" + backend.name + "/" + sequence.name +
                    "/seed" + std::to_string(seed);
            gc.where = scene.pointer + ", " + config.pointer + ", " + backend.pointer + ", " + sequence.pointer;
            gc.arguments = {"crosscheck", scene.input};
            if (!scene.recorded) gc.arguments.insert(gc.arguments.end(), trace.begin(), trace.end());
            gc.arguments.insert(gc.arguments.end(), {"--seed", std::to_string(seed)});
            for (const Named* set : {&config, &sequence}) {
              const std::vector<std::string> a = Arguments(*set, folder, skipped, error);
              gc.arguments.insert(gc.arguments.end(), a.begin(), a.end());
            }
            const std::vector<std::string> b = Arguments(backend, folder, {"backend"}, error);
            gc.arguments.insert(gc.arguments.end(), b.begin(), b.end());
            const std::string checked = backend.options["backend"].get<std::string>();
            gc.arguments.insert(gc.arguments.end(), {"--backends", "reference," + checked});
            gate.cases.push_back(std::move(gc));
          }
        }
      }
    }
  }
}

}  // namespace hpsf::gate
