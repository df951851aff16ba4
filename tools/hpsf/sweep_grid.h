// The grid of `hpsf sweep`: "spp=1,2,4; filter-width=2,4,8; method=pt,hpsf,radius; backend=reference,
// emulated" names axes and their values; the sweep runs every combination. Three axes are the sweep's own:
//   spp      samples per pixel traced (default 4)
//   method   pt (plain path tracing: the batch unfiltered), hpsf (hashed path space filtering on a backend),
//            radius (radius-search path space filtering), screen (screen-space, 9x9) (default hpsf)
//   backend  reference, emulated or vulkan: which backend runs hpsf (default reference)
// Every other axis is an option of `hpsf render`'s filter (filter-width, jitter, normal, fingerprint-bits,
// probe-limit, accum, capacity, ...), written without its dashes, checked by that option layer. A combination that
// differs from an earlier one only in an axis its method ignores (the backend or the filter options of pt, the
// backend of radius and screen) is the same configuration and is run once.
#ifndef HPSF_TOOLS_HPSF_SWEEP_GRID_H
#define HPSF_TOOLS_HPSF_SWEEP_GRID_H

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace hpsf {

struct GridAxis {
  std::string name;
  std::vector<std::string> values;
};

struct SweepConfig {
  std::string id;  // "method=hpsf backend=emulated spp=4 filter-width=2": method, backend, spp, then the filter axes
  std::string method = "hpsf";
  std::string backend = "reference";
  std::uint32_t spp = 4;
  std::vector<std::pair<std::string, std::string>> filter;  // the filter axes' values, in axis order
  // The filter options as command-line words ("--filter-width", "2", ...).
  std::vector<std::string> FilterArguments() const;
};

// A ConfigError naming --grid for an empty axis, a repeated axis, a bad spp, method or backend value.
std::vector<GridAxis> ParseGrid(const std::string& text);

// Every combination, the last axis varying fastest, with the combinations a method ignores merged into the first.
std::vector<SweepConfig> ExpandGrid(const std::vector<GridAxis>& axes);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_SWEEP_GRID_H
