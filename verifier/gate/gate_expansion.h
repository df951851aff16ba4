// What every family of a gate file (verifier/gate/gate_file.h) is expanded with: errors naming the file and the JSON
// pointer of the place, option sets written without their dashes, named groups of them, paths relative to the
// gate file, and seed lists. Each family's expansion (gate_families.h) is built from these, so every family reads
// its part of the file the same way.
#ifndef HPSF_VERIFIER_GATE_GATE_EXPANSION_H
#define HPSF_VERIFIER_GATE_GATE_EXPANSION_H

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hpsf::gate {

class GateError {
 public:
  explicit GateError(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void At(const std::string& pointer, const std::string& problem) const;

 private:
  std::string source_;
};

// Every key of `object` must be in `known`.
void RequireKeys(const nlohmann::json& object, const std::set<std::string>& known, const std::string& pointer,
                 const GateError& error);

// A named set of command options, {"capacity": 512, "accum": "float32"}.
struct Named {
  std::string name;
  std::string pointer;
  nlohmann::json options;
};

// A group of named option sets ({"name": {"option": value, ...}, ...}), names sorted (json objects are). Absent
// from `family`: `fallback` (which must be an object of named sets).
std::vector<Named> NamedOptions(const nlohmann::json& family, const std::string& key, const nlohmann::json& fallback,
                                const std::string& pointer, const GateError& error);

// A set's options as command-line words, `skipped` left out; the paths of accumulate-spv and eviction-spv resolved
// against `folder`. Strings as they are, integers in decimal, other numbers as JSON writes them, true as a bare flag
// (false drops the option).
std::vector<std::string> Arguments(const Named& set, const std::string& folder, const std::set<std::string>& skipped,
                                   const GateError& error);

// A path from the file, relative to the file's folder (absolute paths as they are).
std::string Resolve(const std::string& path, const std::string& folder);

// `family[key]`, an array of seeds in [0, 2^32); {1} when absent.
std::vector<std::uint32_t> Seeds(const nlohmann::json& family, const std::string& pointer, const GateError& error);

// A scene entry: a built-in name, a scene file or a recorded .hpsfv sequence.
struct SceneEntry {
  std::string input;  // as the command line takes it (files resolved)
  std::string name;   // in case ids: the built-in name or the file's stem
  bool recorded = false;
  std::string pointer;
};
std::vector<SceneEntry> Scenes(const nlohmann::json& family, const std::string& pointer, const std::string& folder,
                               const GateError& error);

// The traced image's size and samples ("size": "32x32", "spp": 2 by default) as options.
std::vector<std::string> TraceArguments(const nlohmann::json& family, const std::string& pointer,
                                        const GateError& error);

}  // namespace hpsf::gate

#endif  // HPSF_VERIFIER_GATE_GATE_EXPANSION_H
