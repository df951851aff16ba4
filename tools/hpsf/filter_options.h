// The filter options shared by `hpsf render` and `hpsf replay`, parsed into a validated FilterConfig: a bad
// value is a ConfigError naming the option (exit code 3).
#ifndef HPSF_TOOLS_HPSF_FILTER_OPTIONS_H
#define HPSF_TOOLS_HPSF_FILTER_OPTIONS_H

#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/filter_config.h"
#include "core/filter_result.h"

namespace hpsf {

struct FilterOptions {
  FilterConfig config;
  std::string normal = "sign";
  std::string lod = "on";
  std::string accumulation = "fixed64";
  bool no_filter = false;
};

void AddFilterOptions(CLI::App& command, FilterOptions& options);
FilterConfig ResolveFilterConfig(const FilterOptions& options);

nlohmann::json ToJson(const FilterConfig& config);
nlohmann::json ToJson(const FilterStats& stats);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_FILTER_OPTIONS_H
