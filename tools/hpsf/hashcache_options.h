// The HashCache's options of `hpsf crosscheck` (--method hashcache): its resolution, caching along subpaths and update
// rule, resolved into the run's settings (verifier/contract/hashcache_run.h) and the tracer's cache sampling
// (tracer/cache_sampling.h), every bad value a ConfigError naming its option.
#ifndef HPSF_TOOLS_HPSF_HASHCACHE_OPTIONS_H
#define HPSF_TOOLS_HPSF_HASHCACHE_OPTIONS_H

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "tracer/cache_sampling.h"
#include "verifier/contract/hashcache_run.h"

namespace hpsf {

struct HashCacheFlags {
  std::string method = "table";        // --method: table (hpsf's own) or hashcache
  int resolution_log2 = 7;             // --cache-resolution
  std::uint32_t store = 3;             // --cache-store
  std::uint32_t length = 3;            // --cache-length
  std::string update = "sort-reduce";  // --cache-update: sort-reduce or atomics
  std::string defect = "none";         // --cache-defect: none, plain-store-claim or reduce-off-by-one
};

void AddHashCacheOptions(CLI::App* command, HashCacheFlags& flags);

// Whether --method names the HashCache; a ConfigError for a method that is neither.
bool HashCacheMethod(const HashCacheFlags& flags);
HashCacheSettings ResolveHashCacheSettings(const HashCacheFlags& flags, Accumulation accumulation, std::uint32_t frames,
                                           std::uint32_t seed);
CacheSampling ResolveCacheSampling(const HashCacheFlags& flags);
HashCacheUpdateDefect ResolveCacheDefect(const HashCacheFlags& flags);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_HASHCACHE_OPTIONS_H
