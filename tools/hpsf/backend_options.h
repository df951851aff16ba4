// Which backend filters a batch and what it reports (the options come from emulator_options.h): shared by render,
// replay and crosscheck.
#ifndef HPSF_TOOLS_HPSF_BACKEND_OPTIONS_H
#define HPSF_TOOLS_HPSF_BACKEND_OPTIONS_H

#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/backend.h"
#include "core/filter_config.h"
#include "core/image.h"
#include "core/record.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "reference/reference_filter.h"
#include "verifier/contract/crosscheck.h"
#include "tools/hpsf/emulator_options.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf {

// Backends this build has: reference, emulated, vulkan.
void CheckBackend(const std::string& backend);

struct BackendOutput {
  Image image;
  nlohmann::json stats;
  std::optional<FilterResult> reference;
  std::optional<EmulatedRun> emulated;
  std::optional<VulkanRun> vulkan;
};

// A backend (core/backend.h) with what it needs kept alive: the Vulkan device, which the backend uses.
struct BackendInstance {
  std::unique_ptr<VulkanDevice> device;  // declared first: destroyed after the backend
  std::unique_ptr<Backend> backend;
  EmulatorOptions emulator;
};

BackendInstance MakeBackend(const std::string& backend, const EmulatorOptions& emulator, Defect defect = Defect::kNone,
                            const VulkanBackendOptions& vulkan = {});

// The last frame the backend filtered, as render and replay report it.
BackendOutput LastFrameOutput(const BackendInstance& instance);

// The last frame's eviction, for a report's per-frame entry: cells_evicted (reference), or evicted, tombstones
// and eviction_s, the evict and reclaim passes' time (hashed backends).
nlohmann::json LastFrameEviction(const BackendInstance& instance);
// The temporal blend's pass time of the last frame: {"temporal_s": seconds} for a hashed backend; the reference
// blends inside its filter ({}).
nlohmann::json LastFrameTemporal(const BackendInstance& instance);
// The last frame's level seeds (--level-change seed): cells_seeded (reference), or seeded and level_seed_s, the
// seed pass's time (hashed backends).
nlohmann::json LastFrameLevelSeed(const BackendInstance& instance);

nlohmann::json ToJson(const EmulatedRun& run, const EmulatorOptions& options);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_BACKEND_OPTIONS_H
