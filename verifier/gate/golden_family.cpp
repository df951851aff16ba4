// The gate's golden family (gate_families.h): one case per golden case of a manifest (all of them, or those the
// gate names), each one `hpsf golden check --manifest M NAME`, which renders the case with each of its backends
// and compares the image with its golden (exit 1 warns, 2 fails).
#include <algorithm>

#include "verifier/gate/gate_families.h"
#include "verifier/gate/golden_manifest.h"

namespace hpsf::gate {

using nlohmann::json;

void ExpandGolden(const json& g, const std::string& folder, const GateError& error, Gate& gate) {
  const std::string at = "/golden";
  if (!g.is_object()) error.At(at, "expected an object");
  RequireKeys(g, {"manifest", "cases"}, at, error);
  if (!g.contains("manifest") || !g["manifest"].is_string()) {
    error.At(at + "/manifest", "expected the golden manifest's path");
  }
  const std::string path = Resolve(g["manifest"].get<std::string>(), folder);
  const GoldenManifest manifest = ReadGoldenManifest(path);  // a bad manifest names itself
  std::vector<std::string> names;
  if (g.contains("cases")) {
    if (!g["cases"].is_array() || g["cases"].empty()) error.At(at + "/cases", "expected a non-empty array of names");
    for (std::size_t i = 0; i < g["cases"].size(); ++i) {
      const json& name = g["cases"][i];
      const std::string where = at + "/cases/" + std::to_string(i);
      const bool known = name.is_string() && std::any_of(manifest.cases.begin(), manifest.cases.end(),
                                                         [&](const GoldenCase& c) { return c.name == name; });
      if (!known) error.At(where, "not a case of " + path);
      names.push_back(name.get<std::string>());
    }
    std::sort(names.begin(), names.end());
  } else {
    for (const GoldenCase& c : manifest.cases) names.push_back(c.name);
  }
  for (const std::string& name : names) {
    GateCase gc;
    gc.family = "golden";
    gc.id = "golden/" + name;
    gc.where = at + "/manifest";
    gc.arguments = {"golden", "check", "--manifest", path, name};
    gate.cases.push_back(std::move(gc));
  }
}

}  // namespace hpsf::gate
