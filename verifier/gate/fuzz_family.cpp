// The gate's fuzz family (gate_families.h): backend x seed, each case one `hpsf fuzz --runs N --seed S`. The budget
// is a number of runs, not of seconds: the same seed and runs judge the same batches on every machine, so a gate
// case passes or fails the same everywhere (a time budget would judge more batches on a faster runner).
#include "verifier/gate/gate_families.h"

namespace hpsf::gate {

using nlohmann::json;

void ExpandFuzz(const json& f, const std::string& folder, const GateError& error, Gate& gate) {
  const std::string at = "/fuzz";
  if (!f.is_object()) error.At(at, "expected an object");
  if (f.contains("time")) {
    error.At(at + "/time", "a gate's fuzz budget is \"runs\": the same runs judge the same batches on any machine");
  }
  RequireKeys(f, {"runs", "seeds", "max-records", "backends"}, at, error);
  if (!f.contains("runs") || !f["runs"].is_number_unsigned() || f["runs"].get<std::uint64_t>() == 0) {
    error.At(at + "/runs", "expected the budget: a positive number of runs per backend and seed");
  }
  const std::vector<std::uint32_t> seeds = Seeds(f, at, error);
  if (!f.contains("backends")) error.At(at + "/backends", "expected an object of named backends");
  const std::vector<Named> backends = NamedOptions(f, "backends", json(), at, error);
  std::vector<std::string> budget = {"--runs", std::to_string(f["runs"].get<std::uint64_t>())};
  if (f.contains("max-records")) {
    if (!f["max-records"].is_number_unsigned()) error.At(at + "/max-records", "expected a positive integer");
    budget.insert(budget.end(), {"--max-records", std::to_string(f["max-records"].get<std::uint64_t>())});
  }
  for (const Named& backend : backends) {
    for (const std::uint32_t seed : seeds) {
      GateCase gc;
      gc.family = "fuzz";
      gc.id = "fuzz/" + backend.name + "/seed" + std::to_string(seed);
      gc.where = backend.pointer;
      gc.arguments = {"fuzz", "--seed", std::to_string(seed)};
      gc.arguments.insert(gc.arguments.end(), budget.begin(), budget.end());
      const std::vector<std::string> b = Arguments(backend, folder, {}, error);
      gc.arguments.insert(gc.arguments.end(), b.begin(), b.end());
      gate.cases.push_back(std::move(gc));
    }
  }
}

}  // namespace hpsf::gate
