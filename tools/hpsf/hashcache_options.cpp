#include "tools/hpsf/hashcache_options.h"

#include "core/error.h"

namespace hpsf {

void AddHashCacheOptions(CLI::App* c, HashCacheFlags& f) {
  c->add_option("--method", f.method,
                "What is cross-checked: table (hpsf's hash table) or hashcache (Roth et al.'s HashCache: its "
                "construction and every frame's update on each backend, judged by the family's checker)")
      ->capture_default_str();
  c->add_option("--cache-resolution", f.resolution_log2,
                "--method hashcache: 2^L finest cells per axis over the scene, L in [2, 10]")
      ->capture_default_str();
  c->add_option("--cache-store", f.store, "--method hashcache: l_store, the vertices of each path cached, 1..8")
      ->capture_default_str();
  c->add_option("--cache-length", f.length,
                "--method hashcache: l_len, the vertices whose light each cached vertex carries, 1..8")
      ->capture_default_str();
  c->add_option("--cache-update", f.update,
                "--method hashcache: sort-reduce (Roth's) or atomics (every sample at every level; fixed64 only)")
      ->capture_default_str();
  c->add_option("--cache-defect", f.defect,
                "--method hashcache: a broken update to see caught: plain-store-claim (the front claimed by a load "
                "and a store; emulated and vulkan) or reduce-off-by-one (a segment takes the next one's first "
                "element; emulated)")
      ->capture_default_str();
}

bool HashCacheMethod(const HashCacheFlags& f) {
  if (f.method != "table" && f.method != "hashcache") {
    throw ConfigError("--method", "expected table or hashcache; got '" + f.method + "'");
  }
  return f.method == "hashcache";
}

HashCacheSettings ResolveHashCacheSettings(const HashCacheFlags& f, Accumulation accumulation, std::uint32_t frames,
                                           std::uint32_t seed) {
  if (f.update != "sort-reduce" && f.update != "atomics") {
    throw ConfigError("--cache-update", "expected sort-reduce or atomics; got '" + f.update + "'");
  }
  HashCacheSettings settings;
  settings.resolution_log2 = f.resolution_log2;
  settings.accumulation = accumulation;
  settings.seed = seed;
  settings.frames = frames;
  settings.update = f.update == "atomics" ? HashCacheUpdateRule::kAtomics : HashCacheUpdateRule::kSortAndReduce;
  settings.Validate();
  return settings;
}

CacheSampling ResolveCacheSampling(const HashCacheFlags& f) {
  const CacheSampling sampling{f.store, f.length};
  sampling.Validate();
  return sampling;
}

HashCacheUpdateDefect ResolveCacheDefect(const HashCacheFlags& f) {
  if (f.defect == "none") return HashCacheUpdateDefect::kNone;
  if (f.defect == "plain-store-claim") return HashCacheUpdateDefect::kPlainStoreClaim;
  if (f.defect == "reduce-off-by-one") return HashCacheUpdateDefect::kReduceOffByOne;
  throw ConfigError("--cache-defect", "expected none, plain-store-claim or reduce-off-by-one; got '" + f.defect + "'");
}

}  // namespace hpsf
