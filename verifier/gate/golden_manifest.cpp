#include "verifier/gate/golden_manifest.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "verifier/gate/json_text.h"

namespace hpsf {
namespace {

std::string Where(const std::string& path, std::size_t index, const std::string& name) {
  return path + ": case " + std::to_string(index) + (name.empty() ? "" : " (" + name + ")");
}

}  // namespace

std::string ToString(GoldenComparison comparison) {
  return comparison == GoldenComparison::kExact ? "exact" : "statistical";
}

std::vector<std::string> GoldenCase::Command(const std::string& backend, const std::string& output) const {
  std::vector<std::string> command;
  if (!records.empty()) {
    command = {"replay", records};
  } else {
    command = {"render", scene};
  }
  command.insert(command.end(), args.begin(), args.end());
  command.insert(command.end(), {"--backend", backend, "-o", output});
  if (comparison == GoldenComparison::kStatistical) command.push_back("--variance");
  return command;
}

GoldenManifest ReadGoldenManifest(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the golden manifest");
  nlohmann::json json = ParseJsonText(std::string(std::istreambuf_iterator<char>(in), {}), path);
  if (!json.is_object() || json.value("hpsf_golden", 0) != 1 || !json.contains("cases") || !json["cases"].is_array()) {
    throw InputError(path + ": expected {\"hpsf_golden\": 1, \"cases\": [...]}");
  }
  GoldenManifest manifest;
  manifest.path = path;
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  manifest.folder = folder.empty() ? "." : folder.string();
  std::set<std::string> names;
  const std::set<std::string> known = {"name",       "scene",  "records", "args", "backends", "golden",
                                       "comparison", "metric", "warn",    "fail", "alpha"};
  for (std::size_t i = 0; i < json["cases"].size(); ++i) {
    const nlohmann::json& c = json["cases"][i];
    const std::string name =
        c.is_object() && c.contains("name") && c["name"].is_string() ? c["name"].get<std::string>() : "";
    const std::string where = Where(path, i, name);
    if (!c.is_object()) throw InputError(where + ": expected an object");
    for (const auto& [key, value] : c.items()) {
      if (!known.count(key)) throw InputError(where + ": unknown field '" + key + "'");
    }
    GoldenCase g;
    try {
      g.name = c.at("name").get<std::string>();
      if (c.contains("scene")) g.scene = c["scene"].get<std::string>();
      if (c.contains("records")) g.records = c["records"].get<std::string>();
      g.args = c.value("args", std::vector<std::string>{});
      g.backends = c.at("backends").get<std::vector<std::string>>();
      g.golden = (folder / c.at("golden").get<std::string>()).string();
      const std::string comparison = c.value("comparison", "exact");
      if (comparison != "exact" && comparison != "statistical") {
        throw InputError(where + ": comparison must be exact or statistical, not '" + comparison + "'");
      }
      g.comparison = comparison == "exact" ? GoldenComparison::kExact : GoldenComparison::kStatistical;
      g.thresholds.metric = ParseDiffMetric(c.value("metric", "max"));
      g.thresholds.fail = c.value("fail", 0.0);
      g.thresholds.warn = c.value("warn", g.thresholds.fail);
      g.alpha = c.value("alpha", 0.01);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(where + ": " + e.what());
    } catch (const ConfigError& e) {
      throw InputError(where + ": " + e.what());
    }
    if (g.scene.empty() == g.records.empty()) throw InputError(where + ": give exactly one of scene and records");
    if (g.backends.empty()) throw InputError(where + ": backends is empty");
    if (!(g.alpha > 0.0 && g.alpha < 1.0)) throw InputError(where + ": alpha must lie in (0, 1)");
    if (!names.insert(g.name).second) throw InputError(where + ": a second case of this name");
    manifest.cases.push_back(std::move(g));
  }
  if (manifest.cases.empty()) throw InputError(path + ": no cases");
  return manifest;
}

}  // namespace hpsf
