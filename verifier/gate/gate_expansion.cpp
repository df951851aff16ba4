#include "verifier/gate/gate_expansion.h"

#include <filesystem>

#include "core/error.h"

namespace hpsf::gate {

using nlohmann::json;

void GateError::At(const std::string& pointer, const std::string& problem) const {
  throw InputError(source_ + ": " + pointer + ": " + problem);
}

void RequireKeys(const json& object, const std::set<std::string>& known, const std::string& pointer,
                 const GateError& error) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    if (!known.contains(it.key())) error.At(pointer + "/" + it.key(), "not a gate key");
  }
}

namespace {

std::vector<std::string> OptionArguments(const std::string& name, const json& value, const std::string& pointer,
                                         const GateError& error) {
  if (name.empty() || name[0] == '-') error.At(pointer, "write an option without its dashes");
  const std::string option = "--" + name;
  if (value.is_string()) return {option, value.get<std::string>()};
  if (value.is_number_integer() || value.is_number_unsigned() || value.is_number_float()) return {option, value.dump()};
  if (value.is_boolean()) return value.get<bool>() ? std::vector<std::string>{option} : std::vector<std::string>{};
  error.At(pointer, "an option's value is a string, a number or a boolean");
}

bool IsPathOption(const std::string& name) {
  return name == "accumulate-spv" || name == "eviction-spv" || name == "temporal-spv" || name == "resolve-spv" ||
         name == "compaction-spv" || name == "transport-spv" || name == "table";
}

bool IsFile(const std::string& scene) {
  return scene.find('/') != std::string::npos || scene.find('.') != std::string::npos;
}

}  // namespace

std::string Resolve(const std::string& path, const std::string& folder) {
  const std::filesystem::path p(path);
  return p.is_absolute() || folder.empty() ? path : (std::filesystem::path(folder) / p).lexically_normal().string();
}

std::vector<Named> NamedOptions(const json& family, const std::string& key, const json& fallback,
                                const std::string& pointer, const GateError& error) {
  const json& group = family.contains(key) ? family[key] : fallback;
  const std::string at = pointer + "/" + key;
  if (!group.is_object() || group.empty()) error.At(at, "expected an object of named option sets, not empty");
  std::vector<Named> named;
  for (auto it = group.begin(); it != group.end(); ++it) {
    const std::string where = at + "/" + it.key();
    if (it.key().empty() || it.key().find('/') != std::string::npos) error.At(where, "a name without '/', not empty");
    if (!it.value().is_object()) error.At(where, "expected an object of options");
    named.push_back({it.key(), where, it.value()});
  }
  return named;
}

std::vector<std::string> Arguments(const Named& set, const std::string& folder, const std::set<std::string>& skipped,
                                   const GateError& error) {
  std::vector<std::string> arguments;
  for (auto it = set.options.begin(); it != set.options.end(); ++it) {
    if (skipped.contains(it.key())) continue;
    std::vector<std::string> option = OptionArguments(it.key(), it.value(), set.pointer + "/" + it.key(), error);
    if (IsPathOption(it.key()) && option.size() == 2) option[1] = Resolve(option[1], folder);
    arguments.insert(arguments.end(), option.begin(), option.end());
  }
  return arguments;
}

std::vector<std::uint32_t> Seeds(const json& family, const std::string& pointer, const GateError& error) {
  if (!family.contains("seeds")) return {1};
  const json& list = family["seeds"];
  if (!list.is_array() || list.empty()) error.At(pointer + "/seeds", "expected a non-empty array of seeds");
  std::vector<std::uint32_t> seeds;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& s = list[i];
    if (!s.is_number_unsigned() || s.get<std::uint64_t>() > 0xFFFFFFFFu) {
      error.At(pointer + "/seeds/" + std::to_string(i), "expected an integer in [0, 2^32)");
    }
    seeds.push_back(s.get<std::uint32_t>());
  }
  return seeds;
}

std::vector<SceneEntry> Scenes(const json& family, const std::string& pointer, const std::string& folder,
                               const GateError& error) {
  if (!family.contains("scenes") || !family["scenes"].is_array() || family["scenes"].empty()) {
    error.At(pointer + "/scenes", "expected a non-empty array of scenes (built-in names, scene files, .hpsfv files)");
  }
  std::vector<SceneEntry> scenes;
  for (std::size_t s = 0; s < family["scenes"].size(); ++s) {
    const json& entry = family["scenes"][s];
    SceneEntry scene;
    scene.pointer = pointer + "/scenes/" + std::to_string(s);
    if (!entry.is_string() || entry.get<std::string>().empty()) error.At(scene.pointer, "expected a scene");
    const std::string text = entry.get<std::string>();
    const bool file = IsFile(text);
    scene.recorded = std::filesystem::path(text).extension() == ".hpsfv";
    scene.input = file ? Resolve(text, folder) : text;
    scene.name = file ? std::filesystem::path(text).stem().string() : text;
    scenes.push_back(std::move(scene));
  }
  return scenes;
}

std::vector<std::string> TraceArguments(const json& family, const std::string& pointer, const GateError& error) {
  if (family.contains("size") && !family["size"].is_string()) {
    error.At(pointer + "/size", "expected WIDTHxHEIGHT as a string");
  }
  if (family.contains("spp") && !family["spp"].is_number_unsigned()) {
    error.At(pointer + "/spp", "expected a positive integer");
  }
  return {"--size", family.value("size", "32x32"), "--spp", std::to_string(family.value("spp", 2u))};
}

}  // namespace hpsf::gate
