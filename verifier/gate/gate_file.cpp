#include "verifier/gate/gate_file.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "verifier/gate/gate_families.h"
#include "verifier/gate/gate_schema.h"
#include "verifier/gate/json_schema.h"
#include "verifier/gate/json_text.h"

namespace hpsf {
namespace {

using nlohmann::json;

// The built-in gate: every built-in backend, both accumulation modes, every probing scheme, crowded tables, one frame
// and a sequence with eviction and a blending temporal mode, on the Cornell box and the furnace; their statistics in a
// roomy and a small table; and a fuzz budget for each backend. Tables of 8192 slots: the faithful emulator steps every
// slot of the passes after the accumulate (a 2^22-slot table takes minutes there). No goldens: they live in a project's
// manifest, which a gate file names.
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
      "float32": {"capacity": 8192, "accum": "float32"},
      "buckets": {"capacity": 8192, "probing": "bucket:16"},
      "window-crowded": {"capacity": 512, "probing": "bucket-window:4", "fingerprint-bits": 8}
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
  },
  "statistics": {
    "scenes": ["cornell", "furnace"],
    "size": "64x64",
    "spp": 1,
    "configs": {
      "default": {"capacity": 8192},
      "small": {"capacity": 4096, "fingerprint-bits": 8}
    }
  },
  "fuzz": {
    "runs": 1000,
    "backends": {
      "emulated": {"backend": "emulated"},
      "vulkan": {"backend": "vulkan"}
    }
  }
})";

}  // namespace

Gate ExpandGate(const std::string& text, const std::string& source, const std::string& folder) {
  const gate::GateError error(source);
  json document = ParseJsonText(text, source);
  if (!document.is_object()) error.At("", "expected an object");
  if (!document.contains("hpsf_gate") || document["hpsf_gate"] != kGateFileVersion) {
    error.At("/hpsf_gate", "expected 1, the gate file's version");
  }
  gate::RequireKeys(document, {"hpsf_gate", "name", "crosscheck", "statistics", "golden", "fuzz", "captures"}, "",
                    error);
  Gate gate;
  gate.source = source;
  using Expansion = void (*)(const json&, const std::string&, const gate::GateError&, Gate&);
  const std::pair<const char*, Expansion> families[] = {{"crosscheck", gate::ExpandCrosscheck},
                                                        {"statistics", gate::ExpandStatistics},
                                                        {"golden", gate::ExpandGolden},
                                                        {"fuzz", gate::ExpandFuzz},
                                                        {"captures", gate::ExpandCaptures}};
  for (const auto& [name, expand] : families) {
    if (document.contains(name)) expand(document[name], folder, error, gate);
  }
  if (gate.cases.empty()) {
    throw InputError(source + ": the gate declares no family to run: crosscheck, statistics, golden, fuzz or captures");
  }
  std::set<std::string> ids;
  for (const GateCase& c : gate.cases) {
    if (!ids.insert(c.id).second) error.At(c.where, "two cases share the id " + c.id);
  }
  // The published schema, which editors and CI linters check a gate file by: a file the checks above accept must
  // conform to it too, so the two cannot drift apart unnoticed.
  const std::vector<std::string> violations = SchemaViolations(json::parse(kGateSchemaJson), document);
  if (!violations.empty()) error.At("", "does not conform to the gate file's schema: " + violations.front());
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
