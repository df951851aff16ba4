#include "verifier/contract/hashcache_run.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <utility>

#include "core/cuckoo_map.h"
#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "core/hashcache_check.h"
#include "core/hashcache_update.h"
#include "emulated/cuckoo_kernels.h"
#include "emulated/hashcache_update_kernels.h"
#include "emulated/occupancy_kernels.h"
#include "vulkan/cuckoo_pass.h"
#include "vulkan/occupancy_pass.h"

namespace hpsf {
namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

void HashCacheSettings::Validate() const {
  if (resolution_log2 < shared::kMinOccupancyResolutionLog2 || resolution_log2 > shared::kMaxOccupancyResolutionLog2) {
    throw ConfigError("--cache-resolution", "must lie in [" + std::to_string(shared::kMinOccupancyResolutionLog2) +
                                                ", " + std::to_string(shared::kMaxOccupancyResolutionLog2) +
                                                "] (2^L finest cells per axis); got " +
                                                std::to_string(resolution_log2));
  }
  if (accumulation == Accumulation::kPackedDecimal) {
    throw ConfigError("--accum", "the HashCache keeps fixed64 or float32 sums, not packed-decimal");
  }
  if (frames == 0) throw ConfigError("--frames", "must be at least 1");
  if (update == HashCacheUpdateRule::kAtomics && accumulation != Accumulation::kFixed64) {
    throw ConfigError("--cache-update", "atomics sums fixed64 only: float32 by atomic adds depends on their order");
  }
}

HashCacheRun::HashCacheRun(const BackendInfo& backend, HashCacheSettings settings, EmulatorOptions emulator,
                           VulkanDevice* device, HashCacheUpdateDefect defect)
    : backend_(backend), settings_(settings), emulator_(std::move(emulator)), device_(device), defect_(defect) {
  settings_.Validate();
  if (backend_.kind == BackendKind::kVulkan && !device_) throw std::logic_error("the vulkan HashCache needs a device");
  if (backend_.kind == BackendKind::kVulkan && defect_ == HashCacheUpdateDefect::kReduceOffByOne) {
    throw ConfigError("--cache-defect",
                      "reduce-off-by-one is the emulator's; the device's shader has plain-store-claim");
  }
}

bool HashCacheRun::Prepare(std::span<const OccupancyTriangle> triangles, const std::string& where) {
  if (built_from_ && std::equal(triangles.begin(), triangles.end(), built_from_->begin(), built_from_->end())) {
    return false;
  }
  const shared::OccupancyGrid grid = GridOver(triangles, settings_.resolution_log2, where);
  // The reference's pyramid: what every backend's occupancy must equal, and the keys its maps must hold.
  const std::vector<OccupancyLevel> expected = OccupancyPyramid(grid, triangles);
  auto start = Clock::now();
  std::vector<OccupancyLevel> levels;
  for (int level = 0; level <= grid.resolution_log2; ++level) {
    switch (backend_.kind) {
      case BackendKind::kReference:
        levels.push_back(expected[std::size_t(level)]);
        break;
      case BackendKind::kEmulated:
        levels.push_back(VoxelizeEmulated(grid, triangles, level, emulator_).field);
        break;
      case BackendKind::kVulkan:
        levels.push_back(VoxelizeOnDevice(*device_, grid, triangles, level).field);
        break;
    }
    if (!(levels.back() == expected[std::size_t(level)])) {
      problems_.push_back("construction, level " + std::to_string(level) + ": the occupancy is not the reference's");
    }
  }
  timings_.occupancy_ms = MsSince(start);
  start = Clock::now();
  std::vector<CuckooMap> maps;
  timings_.attempts = 0;
  for (const OccupancyLevel& level : levels) {
    const std::vector<std::uint32_t> keys = OccupiedKeys(level);
    const CuckooBuildOptions options{.seed = settings_.seed, .level = std::uint32_t(level.level())};
    const CuckooBuild build = backend_.kind == BackendKind::kReference ? BuildCuckooMap(keys, options)
                              : backend_.kind == BackendKind::kEmulated
                                  ? BuildCuckooMapEmulated(keys, options, emulator_)
                                  : BuildCuckooMapOnDevice(*device_, keys, options);
    timings_.attempts += build.attempts;
    const std::string at = "construction, level " + std::to_string(level.level()) + ": ";
    if (!build.built) problems_.push_back(at + "no map after " + std::to_string(build.attempts) + " attempts");
    for (const std::string& problem : CheckCuckooMap(build.map, keys)) problems_.push_back(at + problem);
    maps.push_back(build.map);
  }
  timings_.maps_ms = MsSince(start);
  timings_.levels_unchanged = 0;
  for (std::size_t l = 0; l < levels.size() && l < built_levels_.size(); ++l) {
    timings_.levels_unchanged += levels[l] == built_levels_[l];
  }
  cache_ = EmptyHashCache(grid, std::move(maps), settings_.accumulation, 0, updates_, settings_.update);
  built_from_.emplace(triangles.begin(), triangles.end());
  built_levels_ = std::move(levels);
  fresh_ = true;
  ++timings_.builds;
  return true;
}

void HashCacheRun::Update(std::span<const HashCacheSample> samples) {
  if (!cache_) throw std::logic_error("a HashCache update before its construction");
  if (fresh_ && settings_.accumulation == Accumulation::kFixed64) {
    std::vector<glm::vec3> lights;
    lights.reserve(samples.size());
    for (const HashCacheSample& s : samples) lights.push_back(s.light);
    cache_->fixed_point_bits = ChooseFixedPointBitsOf(lights, {}, settings_.frames);
  }
  fresh_ = false;
  const HashCache before = *cache_;
  const auto start = Clock::now();
  switch (backend_.kind) {
    case BackendKind::kReference:
      missed_ = UpdateHashCache(*cache_, samples).missed;
      break;
    case BackendKind::kEmulated:
      missed_ = UpdateHashCacheEmulated(*cache_, samples, emulator_, defect_).missed;
      break;
    case BackendKind::kVulkan:
      if (!device_update_) device_update_ = std::make_unique<HashCacheUpdatePass>(*device_);
      missed_ = device_update_->Run(*cache_, samples, defect_ == HashCacheUpdateDefect::kPlainStoreClaim).missed;
      break;
  }
  timings_.update_ms = MsSince(start);
  for (const std::string& problem : CheckHashCacheFrame(before, *cache_, samples)) {
    problems_.push_back("update " + std::to_string(updates_) + ", " + problem);
  }
  ++updates_;
}

HashCacheReconstruction HashCacheRun::Reconstruct(const RecordBatch& primary, float footprint_scale, float jitter_scale,
                                                  std::uint32_t frame) {
  if (!cache_) throw std::logic_error("a HashCache reconstruction before its construction");
  const auto start = Clock::now();
  const shared::HashCacheLookupParams params{cache_->grid, footprint_scale, jitter_scale, settings_.seed, frame};
  HashCacheReconstruction result = ReconstructHashCache(*cache_, primary, params);
  timings_.reconstruct_ms = MsSince(start);
  return result;
}

}  // namespace hpsf
