// The filter options shared by `hpsf render` and `hpsf replay`, parsed into a validated FilterConfig: a bad
// value is a ConfigError naming the option (exit code 3).
#ifndef HPSF_TOOLS_HPSF_FILTER_OPTIONS_H
#define HPSF_TOOLS_HPSF_FILTER_OPTIONS_H

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/filter_config.h"
#include "core/filter_result.h"

namespace hpsf {

struct FilterOptions {
  FilterConfig config;
  std::string normal = "sign";
  std::string lod = "on";
  std::string neighbour_search = "off";  // --neighbour-search: on or off
  std::string transport = "off";         // --transport: on or off
  std::string second_moments = "off";    // --second-moments: on or off
  std::string interpolation = "off";     // --interpolation: off, step:V0:V1 or smooth:V0:V1
  std::string accumulation = "fixed64";
  std::string fixed_point_bits = "auto";
  std::string square_bits = "auto";
  std::string eviction = "none";
  std::string level_change = "none";
  std::string temporal = "integrate";
  std::string compaction = "none";
  std::string key_identity = "fingerprint";
  std::string probing = "linear";
  std::string table;                                // --table: a table declaration (verifier/gate/table_declaration.h)
  const CLI::Option* probe_limit_option = nullptr;  // to tell --probe-limit given from its default
  CLI::App* command = nullptr;                      // to tell the options given from their defaults
  std::vector<std::string> force_effects;           // --force-effect, repeatable
  bool no_filter = false;
  bool variance = false;  // also write each pixel's variance (verifier/metrics/pixel_variance.h)
};

void AddFilterOptions(CLI::App& command, FilterOptions& options);
FilterConfig ResolveFilterConfig(const FilterOptions& options);
// --variance estimates the within-pixel spread from a pixel's own samples, which takes two or more: a ConfigError
// naming --variance otherwise. `source` says where the count came from (--spp, or the record file).
void CheckVarianceSamples(const FilterOptions& options, std::uint32_t samples_per_pixel, const std::string& source);

nlohmann::json ToJson(const FilterConfig& config);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_FILTER_OPTIONS_H
