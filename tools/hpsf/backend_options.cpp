#include "tools/hpsf/backend_options.h"

#include "core/error.h"

namespace hpsf {

BackendInstance MakeBackend(const std::string& backend, const EmulatorOptions& emulator, Defect defect,
                            const VulkanBackendOptions& vulkan) {
  return MakeBackend(FindBackend(backend, "--backend"), BackendSettings{emulator, defect, vulkan});
}

const Image& LastFrameImage(const Backend& backend) {
  if (const FilterResult* exact = backend.LastExactResult()) return exact->image;
  return backend.LastHashedRun()->image;
}

nlohmann::json LastFrameEviction(const Backend& backend) {
  if (const FilterResult* exact = backend.LastExactResult()) return {{"cells_evicted", exact->stats.cells_evicted}};
  const HashedRun& run = *backend.LastHashedRun();
  return {{"evicted", run.evicted},
          {"tombstones", run.tombstones},
          {"eviction_s", backend.LastFrameTimings().eviction_ms / 1e3}};
}

nlohmann::json LastFrameLevelSeed(const Backend& backend) {
  if (const FilterResult* exact = backend.LastExactResult()) return {{"cells_seeded", exact->stats.cells_seeded}};
  return {{"seeded", backend.LastHashedRun()->seeded},
          {"level_seed_s", backend.LastFrameTimings().level_seed_ms / 1e3}};
}

nlohmann::json LastFrameSettle(const Backend& backend) {
  if (const FilterResult* exact = backend.LastExactResult()) return {{"cells_halved", exact->stats.cells_halved}};
  return {{"halved", backend.LastHashedRun()->halved}, {"settle_s", backend.LastFrameTimings().settle_ms / 1e3}};
}

nlohmann::json LastFrameTemporal(const Backend& backend) {
  if (backend.LastExactResult()) return nlohmann::json::object();
  return {{"temporal_s", backend.LastFrameTimings().temporal_ms / 1e3}};
}

nlohmann::json LastFrameCompaction(const Backend& backend) {
  if (backend.LastExactResult()) return nlohmann::json::object();
  return {{"occupied", backend.LastHashedRun()->table.occupied.size()},
          {"compaction_s", backend.LastFrameTimings().compaction_ms / 1e3}};
}

}  // namespace hpsf
