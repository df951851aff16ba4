#include "tools/gate/gate_file.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>

#include "core/error.h"

namespace hpsf {
namespace {

using nlohmann::json;

// The built-in gate: every built-in backend, both accumulation modes, a crowded table, one frame and a sequence
// with eviction and a blending temporal mode, on the Cornell box and the furnace. Tables of 8192 slots: the
// faithful emulator steps every slot of the passes after the accumulate (a 2^22-slot table takes minutes there).
constexpr const char* kDefaultGate = R"({
  "hpsf_gate": 1,
  "crosscheck": {
    "scenes": ["cornell", "furnace"],
    "size": "32x32",
    "spp": 2,
    "seeds": [1],
    "configs": {
      "default": {"capacity": 8192},
      "crowded": {"capacity": 512, "probe-limit": 4, "fingerprint-bits": 8},
      "float32": {"capacity": 8192, "accum": "float32"}
    },
    "backends": {
      "emulated-fast": {"backend": "emulated"},
      "emulated-faithful": {"backend": "emulated", "mode": "faithful", "warp-size": 8, "schedule": "random:1"},
      "vulkan": {"backend": "vulkan"}
    },
    "sequences": {
      "one-frame": {},
      "strict-ema": {"frames": 3, "eviction": "strict", "temporal": "ema:0.5"}
    }
  }
})";

class GateError {
 public:
  explicit GateError(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void At(const std::string& pointer, const std::string& problem) const {
    throw InputError(source_ + ": " + pointer + ": " + problem);
  }

 private:
  std::string source_;
};

void RequireKeys(const json& object, const std::set<std::string>& known, const std::string& pointer,
                 const GateError& error) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    if (!known.contains(it.key())) error.At(pointer + "/" + it.key(), "not a gate key");
  }
}

// An option's value as the command line takes it: strings as they are, integers in decimal, other numbers as JSON
// writes them, true as a bare flag (false drops the option).
std::vector<std::string> OptionArguments(const std::string& name, const json& value, const std::string& pointer,
                                         const GateError& error) {
  if (name.empty() || name[0] == '-') error.At(pointer, "write an option without its dashes");
  const std::string option = "--" + name;
  if (value.is_string()) return {option, value.get<std::string>()};
  if (value.is_number_integer() || value.is_number_unsigned() || value.is_number_float()) return {option, value.dump()};
  if (value.is_boolean()) return value.get<bool>() ? std::vector<std::string>{option} : std::vector<std::string>{};
  error.At(pointer, "an option's value is a string, a number or a boolean");
}

bool IsPathOption(const std::string& name) { return name == "accumulate-spv" || name == "eviction-spv"; }

bool IsFile(const std::string& scene) {
  return scene.find('/') != std::string::npos || scene.find('.') != std::string::npos;
}

std::string Resolve(const std::string& path, const std::string& folder) {
  const std::filesystem::path p(path);
  return p.is_absolute() || folder.empty() ? path : (std::filesystem::path(folder) / p).lexically_normal().string();
}

struct Named {
  std::string name;
  std::string pointer;
  json options;
};

// A group of named option sets ({"name": {"option": value, ...}, ...}), names sorted (json objects are).
std::vector<Named> NamedOptions(const json& group, const std::string& pointer, const GateError& error) {
  if (!group.is_object() || group.empty()) error.At(pointer, "expected an object of named option sets, not empty");
  std::vector<Named> named;
  for (auto it = group.begin(); it != group.end(); ++it) {
    const std::string where = pointer + "/" + it.key();
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

void ExpandCrosscheck(const json& c, const std::string& folder, const GateError& error, Gate& gate) {
  const std::string at = "/crosscheck";
  if (!c.is_object()) error.At(at, "expected an object");
  RequireKeys(c, {"scenes", "size", "spp", "seeds", "configs", "backends", "sequences"}, at, error);
  if (!c.contains("scenes") || !c["scenes"].is_array() || c["scenes"].empty()) {
    error.At(at + "/scenes", "expected a non-empty array of scenes (built-in names, scene files, .hpsfv files)");
  }
  const std::string size = c.value("size", "32x32");
  if (c.contains("size") && !c["size"].is_string()) error.At(at + "/size", "expected WIDTHxHEIGHT as a string");
  if (c.contains("spp") && !c["spp"].is_number_unsigned()) error.At(at + "/spp", "expected a positive integer");
  const std::string spp = std::to_string(c.value("spp", 2u));
  std::vector<std::uint32_t> seeds = {1};
  if (c.contains("seeds")) {
    if (!c["seeds"].is_array() || c["seeds"].empty()) error.At(at + "/seeds", "expected a non-empty array of seeds");
    seeds.clear();
    for (std::size_t i = 0; i < c["seeds"].size(); ++i) {
      const json& s = c["seeds"][i];
      if (!s.is_number_unsigned() || s.get<std::uint64_t>() > 0xFFFFFFFFu) {
        error.At(at + "/seeds/" + std::to_string(i), "expected an integer in [0, 2^32)");
      }
      seeds.push_back(s.get<std::uint32_t>());
    }
  }
  const json empty_set = {{"default", json::object()}};
  const std::vector<Named> configs =
      NamedOptions(c.contains("configs") ? c["configs"] : empty_set, at + "/configs", error);
  if (!c.contains("backends")) error.At(at + "/backends", "expected an object of named backends");
  const std::vector<Named> backends = NamedOptions(c["backends"], at + "/backends", error);
  const std::vector<Named> sequences = NamedOptions(
      c.contains("sequences") ? c["sequences"] : json{{"one-frame", json::object()}}, at + "/sequences", error);
  for (const Named& b : backends) {
    if (!b.options.contains("backend") || !b.options["backend"].is_string()) {
      error.At(b.pointer + "/backend", "expected the backend checked beside the reference: emulated or vulkan");
    }
  }
  for (std::size_t s = 0; s < c["scenes"].size(); ++s) {
    const json& entry = c["scenes"][s];
    const std::string scene_pointer = at + "/scenes/" + std::to_string(s);
    if (!entry.is_string() || entry.get<std::string>().empty()) error.At(scene_pointer, "expected a scene");
    const std::string scene = entry.get<std::string>();
    const bool file = IsFile(scene);
    const bool recorded = std::filesystem::path(scene).extension() == ".hpsfv";
    const std::string input = file ? Resolve(scene, folder) : scene;
    const std::string scene_name = file ? std::filesystem::path(scene).stem().string() : scene;
    for (const Named& config : configs) {
      for (const Named& backend : backends) {
        for (const Named& sequence : sequences) {
          for (const std::uint32_t seed : seeds) {
            GateCase gc;
            gc.family = "crosscheck";
            gc.id = "crosscheck/" + scene_name + "/" + config.name + "/" + backend.name + "/" + sequence.name +
                    "/seed" + std::to_string(seed);
            gc.where = scene_pointer + ", " + config.pointer + ", " + backend.pointer + ", " + sequence.pointer;
            gc.arguments = {"crosscheck", input};
            if (!recorded) gc.arguments.insert(gc.arguments.end(), {"--size", size, "--spp", spp});
            gc.arguments.insert(gc.arguments.end(), {"--seed", std::to_string(seed)});
            for (const Named* set : {&config, &sequence}) {
              const std::vector<std::string> a = Arguments(
                  *set, folder, recorded ? std::set<std::string>{"frames", "frame"} : std::set<std::string>{}, error);
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

}  // namespace

Gate ExpandGate(const std::string& text, const std::string& source, const std::string& folder) {
  const GateError error(source);
  json document;
  try {
    document = json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError(source + ": not valid JSON at byte " + std::to_string(e.byte));
  }
  if (!document.is_object()) error.At("", "expected an object");
  if (!document.contains("hpsf_gate") || document["hpsf_gate"] != kGateFileVersion) {
    error.At("/hpsf_gate", "expected 1, the gate file's version");
  }
  RequireKeys(document, {"hpsf_gate", "name", "crosscheck"}, "", error);
  Gate gate;
  gate.source = source;
  if (!document.contains("crosscheck")) error.At("/crosscheck", "the gate declares no family to run");
  ExpandCrosscheck(document["crosscheck"], folder, error, gate);
  std::set<std::string> ids;
  for (const GateCase& c : gate.cases) {
    if (!ids.insert(c.id).second) error.At(c.where, "two cases share the id " + c.id);
  }
  return gate;
}

Gate ReadGateFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the gate file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return ExpandGate(text, path, std::filesystem::path(path).parent_path().string());
}

Gate DefaultGate() { return ExpandGate(kDefaultGate, "the default gate", ""); }

std::vector<GateCase> ShardOf(const std::vector<GateCase>& cases, std::uint32_t index, std::uint32_t count) {
  std::vector<GateCase> shard;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (i % count == index - 1) shard.push_back(cases[i]);
  }
  return shard;
}

std::pair<std::uint32_t, std::uint32_t> ParseShard(const std::string& text) {
  const std::size_t slash = text.find('/');
  std::uint32_t index = 0, count = 0;
  const bool parsed =
      slash != std::string::npos &&
      std::from_chars(text.data(), text.data() + slash, index).ptr == text.data() + slash && slash > 0 &&
      std::from_chars(text.data() + slash + 1, text.data() + text.size(), count).ptr == text.data() + text.size() &&
      slash + 1 < text.size();
  if (!parsed || count == 0 || index == 0 || index > count) {
    throw ConfigError("--shard", "expected I/N with 1 <= I <= N, as in 2/4; got '" + text + "'");
  }
  return {index, count};
}

}  // namespace hpsf
