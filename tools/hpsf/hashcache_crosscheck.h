// `hpsf crosscheck SCENE --method hashcache`: the HashCache (verifier/contract/hashcache_run.h) on each backend named,
// over the scene's frames, every backend caching the same samples (traced once a frame). Its report is a cross-check
// report (docs/reference/json-reports.md) whose levels are the family's: level 1, each construction (every level's
// occupancy the reference's, every map's invariants); level 2, each frame's update (the reference's given the
// backend's claims, bit for bit). A failure writes a bundle whose reproduce.sh reruns the same command.
#ifndef HPSF_TOOLS_HPSF_HASHCACHE_CROSSCHECK_H
#define HPSF_TOOLS_HPSF_HASHCACHE_CROSSCHECK_H

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tracer/cache_sampling.h"
#include "tracer/scene.h"
#include "tracer/trace_options.h"
#include "verifier/contract/crosscheck.h"
#include "verifier/contract/hashcache_run.h"

namespace hpsf {

struct HashCacheCrosscheck {
  nlohmann::json report;
  std::string text;
  bool passed = true;
};

// trace: the first frame's options (its frame, size, spp and seed); frames: how many from it.
HashCacheCrosscheck CrosscheckHashCache(const Scene& scene, TraceOptions trace, std::uint32_t frames,
                                        const std::vector<std::string>& backends, const HashCacheSettings& settings,
                                        const CacheSampling& sampling, const EmulatorOptions& emulator,
                                        const VulkanBackendOptions& vulkan,
                                        HashCacheUpdateDefect defect = HashCacheUpdateDefect::kNone);

// The bundle of a failed run: report.json, the scene (a file's copy, scene.json; the meshes it names are not copied)
// and reproduce.sh, which reruns `hpsf crosscheck` with `arguments` (the input replaced by the bundle's scene).
void WriteHashCacheBundle(const std::string& dir, const std::string& input, const std::vector<std::string>& arguments,
                          const nlohmann::json& report);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_HASHCACHE_CROSSCHECK_H
