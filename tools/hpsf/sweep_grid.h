// The grid of `hpsf sweep`: "spp=1,2,4; filter-width=2,4,8; method=pt,hpsf,radius; backend=reference,
// emulated" names axes and their values; the sweep runs every combination. These axes are the sweep's own:
//   spp                 samples per pixel traced per frame (default 4)
//   method              pt (plain path tracing: the batch unfiltered), hpsf (hashed path space filtering on a
//                       backend), nhpsf (hpsf with the transport: several filtered bounces), anhpsf (nhpsf with
//                       paths continued across frames), radius (radius-search path space filtering), screen
//                       (screen-space, 9x9), hashcache (Roth et al.'s HashCache on a backend: cached along
//                       subpaths, reconstructed at the footprint's level with the filter's --jitter and
//                       --filter-width, with its --accum) (default hpsf)
//   backend             reference, emulated or vulkan: which backend runs the hashed methods (default reference)
//   frames              frames of a sequence, the image after the last measured (default 1)
//   max-depth           surface vertices per traced path of pt, hpsf, radius and screen (default the sweep's
//                       --max-depth)
//   filtered-vertices   vertices of a path nhpsf and anhpsf filter (default 1)
//   continuation-depth  how deep anhpsf continues a path across frames (default the sweep's --max-depth)
//   survival            hpsf's variance-aware path survival, off or a --survival rule (core/survival.h), with
//                       second moments kept; it acts from a sequence's second frame on (default off)
//   cache-resolution    hashcache: 2^L finest cells per axis, L in [2, 10] (default 7)
//   cache-store         hashcache: l_store, the vertices of a path cached, 1 to 8 (default 3)
//   cache-length        hashcache: l_len, the vertices whose light each cached vertex carries, 1 to 8 (default 3)
//   cache-update        hashcache: sort-reduce (Roth's) or atomics (every sample at every level; fixed64 only)
//                       (default sort-reduce)
//   path-graph          hpsf's adaptive path graphs, off or a --path-graph bound (core/path_graph.h), with second
//                       moments kept; from a sequence's second frame on (default off). Its paths' own light shows
//                       where the resolve takes it: interpolation=path, or a variance rule
// Every other axis is an option of `hpsf render`'s filter (filter-width, jitter, normal, fingerprint-bits,
// probe-limit, accum, capacity, temporal, ...), written without its dashes, checked by that option layer; the
// transport is the methods' own. A combination that differs from an earlier one only in an axis its method ignores
// (the backend or the filter options of pt, the backend of radius and screen, a trace axis another method reads) is
// the same configuration and is run once.
#ifndef HPSF_TOOLS_HPSF_SWEEP_GRID_H
#define HPSF_TOOLS_HPSF_SWEEP_GRID_H

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace hpsf {

struct GridAxis {
  std::string name;
  std::vector<std::string> values;
};

struct SweepConfig {
  // "method=hpsf backend=emulated spp=4 filter-width=2": method, backend, spp, the frames (when not 1), the trace
  // axes the method reads, then the filter axes.
  std::string id;
  std::string method = "hpsf";
  std::string backend = "reference";
  std::uint32_t spp = 4;
  std::uint32_t frames = 1;
  // The trace axes, set where the grid names them and the method reads them.
  std::optional<int> max_depth;
  std::optional<std::uint32_t> filtered_vertices;
  std::optional<std::uint32_t> continuation_depth;
  std::optional<std::string> survival;    // a --survival rule other than off, for hpsf
  std::optional<std::string> path_graph;  // a --path-graph bound other than off, for hpsf
  std::optional<int> cache_resolution;    // hashcache's axes
  std::optional<std::uint32_t> cache_store;
  std::optional<std::uint32_t> cache_length;
  std::optional<std::string> cache_update;
  std::vector<std::pair<std::string, std::string>> filter;  // the filter axes' values, in axis order
  // The filter options as command-line words ("--filter-width", "2", ...).
  std::vector<std::string> FilterArguments() const;
  // Whether a backend's table runs the method (hpsf, nhpsf, anhpsf), and whether it transports (nhpsf, anhpsf).
  bool Hashed() const;
  bool Transports() const;
  // Whether the backend axis chooses where the method runs: the hashed methods and the HashCache.
  bool UsesBackend() const;
};

// A ConfigError naming --grid for an empty axis, a repeated axis, a bad value of one of the sweep's own axes, or the
// axis transport.
std::vector<GridAxis> ParseGrid(const std::string& text);

// Every combination, the last axis varying fastest, with the combinations a method ignores merged into the first.
std::vector<SweepConfig> ExpandGrid(const std::vector<GridAxis>& axes);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_SWEEP_GRID_H
