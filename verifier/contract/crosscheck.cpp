#include "verifier/contract/crosscheck.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "core/backend_registry.h"
#include "core/error.h"
#include "verifier/contract/backend_factory.h"
#include "verifier/contract/contract_levels.h"

namespace hpsf {

// The Vulkan backend and its rerun, on one device.
struct Crosschecker::VulkanContext {
  BackendInstance backend, rerun;  // the rerun on the first one's device
  std::string description;

  explicit VulkanContext(const VulkanBackendOptions& options)
      : backend(MakeBackend(FindBackend("vulkan", "--backends"), {.vulkan = options})),
        rerun(MakeBackend(*backend.info, {.vulkan = options}, backend.device.get())) {
    const VulkanDeviceInfo& info = backend.device->info();
    description = info.name + ", driver " + info.driver_name + " (" + info.driver_info + "), memory " + info.memory;
  }
};

Crosschecker::Crosschecker(const std::vector<std::string>& backends, Defect defect, const VulkanBackendOptions& vulkan)
    : backends_(backends), defect_(defect), vulkan_options_(vulkan) {
  for (const std::string& b : backends_) FindBackend(b, "--backends");
}

Crosschecker::~Crosschecker() = default;

CrosscheckReport Crosschecker::Check(const RecordBatch& batch, const FilterConfig& config,
                                     const EmulatorOptions& emulator) {
  return Judge(std::span<const RecordBatch>(&batch, 1), std::span<const std::uint32_t>(&config.frame, 1), config,
               emulator);
}

CrosscheckReport Crosschecker::CheckFrames(std::span<const RecordBatch> frames, const FilterConfig& config,
                                           const EmulatorOptions& emulator) {
  std::vector<std::uint32_t> numbers;
  for (const RecordBatch& batch : frames) numbers.push_back(batch.frame);
  return Judge(frames, numbers, config, emulator);
}

CrosscheckReport Crosschecker::Judge(std::span<const RecordBatch> frames, std::span<const std::uint32_t> numbers,
                                     const FilterConfig& config, const EmulatorOptions& emulator) {
  auto has = [&](const char* name) { return std::find(backends_.begin(), backends_.end(), name) != backends_.end(); };
  std::vector<JudgedBackend> hashed;
  std::optional<EmulatedPair> emulated;
  if (has("emulated")) {
    emulated.emplace(emulator, defect_);
    hashed.push_back(emulated->Judged());
  }
  if (has("vulkan")) {
    if (vulkan_options_.shader_keys && config.level_seed.enabled) {
      throw ConfigError("--key-source",
                        "level seeding looks cells up by hpsf's key and levels; a shader's own keys "
                        "have neither: drop --level-change");
    }
    if (!vulkan_) vulkan_ = std::make_unique<VulkanContext>(vulkan_options_);
    hashed.push_back({"vulkan", vulkan_->backend.backend.get(), vulkan_->rerun.backend.get(), "rerun on the device",
                      false, true, vulkan_options_.shader_keys});
  }
  CrosscheckReport report = JudgeSequence(frames, numbers, config, hashed, observer_);
  if (has("vulkan")) report.vulkan_device = vulkan_->description;
  return report;
}

CrosscheckReport Crosscheck(const RecordBatch& batch, const FilterConfig& config,
                            const std::vector<std::string>& backends, const EmulatorOptions& emulator, Defect defect,
                            const VulkanBackendOptions& vulkan) {
  return Crosschecker(backends, defect, vulkan).Check(batch, config, emulator);
}

}  // namespace hpsf
