// A HashCache on one backend (reference, emulated or vulkan), as a renderer runs it (Roth et al. §3): its construction
// from a scene's triangles (each level's occupancy and cuckoo map, on the backend), each frame's sort-and-reduce
// update by the frame's cache samples, and the reconstruction of an image. Every construction and every update is held
// to the family's checker as it runs (core/cuckoo_map.h, core/hashcache_check.h): a level whose occupancy is not the
// reference's or whose map breaks an invariant, or an update that is not the reference's given the backend's claims,
// is a problem the run reports.
//
// Effect planning: construction runs where the scene's triangles changed since the last build, and never on a static
// scene's later frames, nor where only the camera moved. A rebuild rebuilds every level and starts the cache empty: the
// light cached in the old geometry's cells lit another scene (a level whose occupancy did not change could keep its
// map, which saves its construction but not its light; the timings count such levels).
#ifndef HPSF_VERIFIER_CONTRACT_HASHCACHE_RUN_H
#define HPSF_VERIFIER_CONTRACT_HASHCACHE_RUN_H

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/backend_registry.h"
#include "core/hashcache.h"
#include "core/hashcache_reconstruct.h"
#include "core/occupancy.h"
#include "emulated/emulated_filter.h"
#include "emulated/hashcache_update_kernels.h"
#include "vulkan/hashcache_update_pass.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

struct HashCacheSettings {
  int resolution_log2 = 7;                             // --cache-resolution: 2^L finest cells per axis, L in [2, 10]
  Accumulation accumulation = Accumulation::kFixed64;  // fixed64 or float32
  std::uint32_t seed = 1;                              // of the maps' hash constants
  std::uint32_t frames = 1;  // frames the cache integrates: fixed64's F keeps their sums below 2^63
  HashCacheUpdateRule update = HashCacheUpdateRule::kSortAndReduce;  // --cache-update: sort-reduce or atomics
  void Validate() const;                                             // ConfigError naming the option
};

struct HashCacheTimings {
  double occupancy_ms = 0.0;  // the last construction's voxelization, every level
  double maps_ms = 0.0;       // and its maps' construction
  double update_ms = 0.0;     // the last update
  double reconstruct_ms = 0.0;
  std::uint32_t builds = 0;    // constructions so far
  std::uint32_t attempts = 0;  // the last construction's map attempts, every level
  // The last rebuild's levels whose occupancy equals the build before's (their maps could have been kept).
  std::uint32_t levels_unchanged = 0;
};

class HashCacheRun {
 public:
  // device: where the vulkan backend runs (it must outlive the run). defect: a broken update, on the emulator (either
  // variant) or the device (the plain-store claim); the reference ignores it.
  HashCacheRun(const BackendInfo& backend, HashCacheSettings settings, EmulatorOptions emulator = {},
               VulkanDevice* device = nullptr, HashCacheUpdateDefect defect = HashCacheUpdateDefect::kNone);

  // Builds the cache over `triangles` where they differ from the last build's (or nothing is built yet); whether it
  // built. `where` names the scene in an InputError for triangles no grid holds.
  bool Prepare(std::span<const OccupancyTriangle> triangles, const std::string& where);
  // One frame's update. fixed64's F is chosen at the first update after a build, for `settings.frames` such frames.
  void Update(std::span<const HashCacheSample> samples);
  // The image of `primary` (a frame's primary hits) from the cache, on the host whatever the backend: the lookups
  // and the fill are the reference's (core/hashcache_reconstruct.h).
  HashCacheReconstruction Reconstruct(const RecordBatch& primary, float footprint_scale, float jitter_scale,
                                      std::uint32_t frame);

  const HashCache& cache() const { return *cache_; }
  const HashCacheTimings& timings() const { return timings_; }
  std::uint64_t missed() const { return missed_; }  // the last update's samples in no occupied cell
  // What the checker found so far, each naming the frame, the level, the slot and the array.
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  const BackendInfo& backend_;
  HashCacheSettings settings_;
  EmulatorOptions emulator_;
  VulkanDevice* device_;
  HashCacheUpdateDefect defect_;
  std::unique_ptr<HashCacheUpdatePass> device_update_;  // vulkan: the update's pipeline, made once
  std::optional<std::vector<OccupancyTriangle>> built_from_;
  std::vector<OccupancyLevel> built_levels_;
  std::optional<HashCache> cache_;
  bool fresh_ = true;  // no update since the build
  std::uint32_t updates_ = 0;
  std::uint64_t missed_ = 0;
  HashCacheTimings timings_;
  std::vector<std::string> problems_;
};

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_HASHCACHE_RUN_H
