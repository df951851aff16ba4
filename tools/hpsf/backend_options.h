// Which backend filters a batch and what it reports (the options come from emulator_options.h): shared by render,
// replay and crosscheck.
#ifndef HPSF_TOOLS_HPSF_BACKEND_OPTIONS_H
#define HPSF_TOOLS_HPSF_BACKEND_OPTIONS_H

#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/filter_config.h"
#include "core/image.h"
#include "core/record.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "reference/reference_filter.h"
#include "tools/checks/crosscheck.h"
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

BackendOutput RunBackend(const std::string& backend, const RecordBatch& batch, const FilterConfig& config,
                         const EmulatorOptions& emulator, Defect defect = Defect::kNone, const VulkanBackendOptions& vulkan = {});

nlohmann::json ToJson(const EmulatedRun& run, const EmulatorOptions& options);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_BACKEND_OPTIONS_H
