#include "verifier/gate/table_declaration.h"

#include <fstream>
#include <functional>
#include <iterator>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "verifier/gate/json_schema.h"
#include "verifier/gate/json_text.h"

namespace hpsf {
namespace {

using nlohmann::json;

constexpr int kTableDeclarationVersion = 1;

// One setting of the declaration: its place, the option it stands for, and how it sets the config from the JSON
// value the schema has already typed. A setter throws ConfigError for a value the option's parser rejects.
struct Setting {
  const char* pointer;
  const char* option;
  std::function<void(const json&, FilterConfig&)> apply;
};

const std::vector<Setting>& Settings() {
  static const std::vector<Setting> settings = {
      {"/capacity", "--capacity", [](const json& v, FilterConfig& c) { c.capacity = v.get<std::uint32_t>(); }},
      {"/probing", "--probing",
       [](const json& v, FilterConfig& c) {
         const Probing p = ParseProbing(v.get<std::string>());
         c.probing = p.kind;
         c.probe_limit = *p.size;  // the schema requires KIND:N
       }},
      {"/key/identity", "--key-identity",
       [](const json& v, FilterConfig& c) { c.key_identity = ParseKeyIdentity(v.get<std::string>()); }},
      {"/key/fingerprint_bits", "--fingerprint-bits",
       [](const json& v, FilterConfig& c) { c.fingerprint_bits = v.get<std::uint32_t>(); }},
      {"/key/normal_in_index", "--normal-in-fingerprint-only",
       [](const json& v, FilterConfig& c) { c.normal_in_index = v.get<bool>(); }},
      {"/sums/encoding", "--accum",
       [](const json& v, FilterConfig& c) { c.accumulation = ParseAccumulation(v.get<std::string>()); }},
      {"/sums/fixed_point_bits", "--fixed-point-bits",
       [](const json& v, FilterConfig& c) {
         if (v.is_string()) {
           c.fixed_point_bits.reset();  // "auto"
         } else {
           c.fixed_point_bits = v.get<int>();
         }
       }},
      {"/passes/eviction", "--eviction",
       [](const json& v, FilterConfig& c) { c.eviction = ParseEviction(v.get<std::string>()); }},
      {"/passes/temporal", "--temporal",
       [](const json& v, FilterConfig& c) { c.temporal = ParseTemporal(v.get<std::string>()); }},
      {"/passes/level_change", "--level-change",
       [](const json& v, FilterConfig& c) { c.level_seed = ParseLevelSeed(v.get<std::string>()); }},
      {"/passes/compaction", "--compaction",
       [](const json& v, FilterConfig& c) { c.compaction = ParseCompaction(v.get<std::string>()); }},
  };
  return settings;
}

// "--option: problem" without its option, which the declaration names by its place instead.
std::string Problem(const ConfigError& e, const std::string& option) {
  const std::string what = e.what();
  const std::string prefix = option + ": ";
  return what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
}

}  // namespace

std::vector<DeclaredSetting> ApplyTableDeclarationText(const std::string& text, const std::string& source,
                                                       FilterConfig& config) {
  const json document = ParseJsonText(text, source);
  if (!document.is_object() || !document.contains("hpsf_table") || document["hpsf_table"] != kTableDeclarationVersion) {
    throw InputError(source + ": /hpsf_table: expected 1, the table declaration's version");
  }
  const std::vector<std::string> violations = SchemaViolations(json::parse(kTableSchemaJson), document);
  if (!violations.empty()) throw InputError(source + ": " + violations.front());

  std::vector<DeclaredSetting> made;
  for (const Setting& s : Settings()) {
    const json::json_pointer pointer(s.pointer);
    if (!document.contains(pointer)) continue;
    try {
      s.apply(document.at(pointer), config);
    } catch (const ConfigError& e) {
      throw InputError(source + ": " + s.pointer + ": " + Problem(e, s.option));
    }
    made.push_back({s.pointer, s.option});
  }
  // The values together (a bucket's size a power of two and at most the capacity, priority's fingerprint width):
  // named by the first setting the failing option stands for, else by the file.
  try {
    config.Validate();
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    for (const DeclaredSetting& d : made) {
      if (what.rfind(d.option + ": ", 0) == 0)
        throw InputError(source + ": " + d.pointer + ": " + Problem(e, d.option));
    }
    if (what.rfind("--probe-limit: ", 0) == 0) {
      for (const DeclaredSetting& d : made) {
        if (d.option == "--probing") throw InputError(source + ": /probing: " + Problem(e, "--probe-limit"));
      }
    }
    throw InputError(source + ": " + what);
  }
  return made;
}

std::string TableDeclarationText(const FilterConfig& config) {
  json document = {
      {"hpsf_table", kTableDeclarationVersion},
      {"name", "written by hpsf"},
      {"capacity", config.capacity},
      {"probing", ToString(config.probing) + ":" + std::to_string(config.probe_limit)},
      {"key", {{"identity", ToString(config.key_identity)}, {"normal_in_index", config.normal_in_index}}},
      {"sums", {{"encoding", ToString(config.accumulation)}}},
      {"passes",
       {{"eviction", config.eviction.ToString()},
        {"temporal", config.temporal.ToString()},
        {"level_change", config.level_seed.ToString()},
        {"compaction", ToString(config.compaction)}}},
  };
  if (config.key_identity == KeyIdentity::kFingerprint) document["key"]["fingerprint_bits"] = config.fingerprint_bits;
  if (config.fixed_point_bits) {
    document["sums"]["fixed_point_bits"] = *config.fixed_point_bits;
  } else {
    document["sums"]["fixed_point_bits"] = "auto";
  }
  return document.dump(2) + "\n";
}

std::vector<DeclaredSetting> ApplyTableDeclaration(const std::string& path, FilterConfig& config) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the table declaration");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return ApplyTableDeclarationText(text, path, config);
}

}  // namespace hpsf
