// Makes the backends of the registry (core/backend_registry.h): each with what it needs kept alive (a Vulkan
// device) and a description of its last frame for reports, written here where the concrete type is known, so no
// tool ever casts a Backend to find out what it is.
#ifndef HPSF_VERIFIER_CONTRACT_BACKEND_FACTORY_H
#define HPSF_VERIFIER_CONTRACT_BACKEND_FACTORY_H

#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "core/backend.h"
#include "core/backend_registry.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "verifier/contract/crosscheck.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

struct BackendSettings {
  EmulatorOptions emulator = {};     // emulated: mode, warp size, schedule, threads
  Defect defect = Defect::kNone;     // emulated: a known defect injected into its accumulate kernel
  VulkanBackendOptions vulkan = {};  // vulkan: the device, its memory placement, a team's shaders
};

struct BackendInstance {
  const BackendInfo* info = nullptr;
  std::unique_ptr<VulkanDevice> device;  // declared first: destroyed after the backend
  std::unique_ptr<Backend> backend;
  // The last frame's statistics as the reports print them: probe failures, wraps, slots used, eviction and seed
  // counts, and "timings_ms" (the hashed backends: each pass, in milliseconds).
  std::function<nlohmann::json()> last_frame_stats;
};

// device: where an on-device backend runs, shared with other backends (the cross-check's rerun); null makes one
// from settings.vulkan, which the instance keeps.
BackendInstance MakeBackend(const BackendInfo& info, const BackendSettings& settings, VulkanDevice* device = nullptr);

// The exact map's statistics, as the reference reports them.
nlohmann::json ToJson(const FilterStats& stats);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CONTRACT_BACKEND_FACTORY_H
