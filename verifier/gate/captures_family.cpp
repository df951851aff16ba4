// The gate's captures family (gate_families.h): one case per capture or folder of captures a team's engine wrote
// (docs/reference/capture-format.md), each one `hpsf judge PATH`, which judges every frame by the checker and the
// contract (exit 2 fails). The paths must exist when the gate is read: a missing one is the gate file's bad input.
#include <algorithm>
#include <filesystem>

#include "verifier/gate/gate_families.h"

namespace hpsf::gate {

using nlohmann::json;

void ExpandCaptures(const json& family, const std::string& folder, const GateError& error, Gate& gate) {
  const std::string at = "/captures";
  if (!family.is_object()) error.At(at, "expected an object");
  RequireKeys(family, {"paths"}, at, error);
  if (!family.contains("paths") || !family["paths"].is_array() || family["paths"].empty()) {
    error.At(at + "/paths", "expected a non-empty array of captures (*.hpsfc) or folders of them");
  }
  std::vector<std::pair<std::string, std::string>> paths;  // as given, resolved
  for (std::size_t i = 0; i < family["paths"].size(); ++i) {
    const json& path = family["paths"][i];
    const std::string where = at + "/paths/" + std::to_string(i);
    if (!path.is_string() || path.get<std::string>().empty()) error.At(where, "expected a path");
    const std::string resolved = Resolve(path.get<std::string>(), folder);
    if (!std::filesystem::exists(resolved)) error.At(where, resolved + ": no such capture or folder");
    paths.emplace_back(path.get<std::string>(), resolved);
  }
  std::sort(paths.begin(), paths.end());
  for (const auto& [given, resolved] : paths) {
    // The id names the path without the climb out of the gate file's folder: "../examples/captures" is
    // "captures/examples/captures".
    std::string name = std::filesystem::path(given).lexically_normal().string();
    while (name.rfind("../", 0) == 0 || name.rfind("./", 0) == 0) name.erase(0, name.find('/') + 1);
    if (name.size() > 1 && name.back() == '/') name.pop_back();
    GateCase c;
    c.family = "captures";
    c.id = "captures/" + name;
    c.where = at + "/paths";
    c.arguments = {"judge", resolved};
    gate.cases.push_back(std::move(c));
  }
}

}  // namespace hpsf::gate
