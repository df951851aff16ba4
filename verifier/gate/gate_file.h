// The gate file of `hpsf check`: a versioned JSON matrix that a team's CI adopts. It declares families
// of cases (verifier/gate/gate_families.h): cross-checks (scenes, named table configurations, named backends, a team's
// SPIR-V accumulate shader being one, named sequences of frames, seeds), statistics, goldens and a fuzz budget.
// Option sets are `hpsf` command options written without their dashes ({"capacity": 512, "accum": "float32"}), so
// a gate case is exactly a command line and the command's own option layer validates it:
//
//   {"hpsf_gate": 1,
//    "crosscheck": {"scenes": ["cornell"], "size": "32x32", "spp": 2, "seeds": [1],
//                   "configs": {"default": {}, "crowded": {"capacity": 256, "probe-limit": 4}},
//                   "backends": {"emulated": {"backend": "emulated"}, "vulkan": {"backend": "vulkan"}},
//                   "sequences": {"one-frame": {}, "strict": {"frames": 3, "eviction": "strict"}}},
//    "statistics": {"scenes": ["cornell"], "size": "64x64", "spp": 1, "configs": {"small": {"capacity": 4096}}},
//    "golden": {"manifest": "golden/manifest.json", "cases": ["cornell/fixed64"]},
//    "fuzz": {"runs": 1000, "seeds": [1], "backends": {"ours": {"backend": "vulkan", "accumulate-spv": "a.spv",
//                                                               "accum": "fixed64"}}}}
//
// A case's id names its family and each coordinate. A bad file is an InputError naming the file and the JSON pointer
// of the place.
#ifndef HPSF_VERIFIER_GATE_GATE_FILE_H
#define HPSF_VERIFIER_GATE_GATE_FILE_H

#include <cstdint>
#include <string>
#include <vector>

namespace hpsf {

inline constexpr int kGateFileVersion = 1;

struct GateCase {
  std::string id;                      // "crosscheck/cornell/crowded/vulkan/strict/seed1"
  std::string family;                  // "crosscheck", "statistics", "golden" or "fuzz"
  std::vector<std::string> arguments;  // after `hpsf`: the command ("crosscheck"), its input, then its options
  std::string where;                   // the gate file's place it came from, for error messages
};

struct Gate {
  std::string source;  // the file, or "the default gate"
  std::vector<GateCase> cases;
};

// Reads and expands a gate file. Relative paths in it (scene files, record files, shaders) are relative to the
// file's folder.
Gate ReadGateFile(const std::string& path);
// The gate `hpsf check` runs without a file: the built-in backends on built-in scenes, cross-checked, their
// statistics and a fuzz budget; a few minutes on 2 cores.
Gate DefaultGate();
// Expands a parsed gate document; `folder` resolves relative paths, `source` names it in errors.
Gate ExpandGate(const std::string& text, const std::string& source, const std::string& folder);

// Cases i with i % count == index - 1 (index in [1, count]): shards 1..count together hold every case once.
std::vector<GateCase> ShardOf(const std::vector<GateCase>& cases, std::uint32_t index, std::uint32_t count);
// Parses "I/N" with 1 <= I <= N; a ConfigError naming --shard otherwise.
std::pair<std::uint32_t, std::uint32_t> ParseShard(const std::string& text);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_GATE_FILE_H
