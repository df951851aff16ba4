// The Vulkan backend behind the Backend interface (core/backend.h): the table stays in device memory from frame
// to frame; each frame's table is read back for the checks.
#ifndef HPSF_VULKAN_VULKAN_BACKEND_H
#define HPSF_VULKAN_VULKAN_BACKEND_H

#include <optional>
#include <string>

#include "core/backend.h"
#include "vulkan/vulkan_device.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf {

class VulkanBackend : public Backend {
 public:
  // accumulate_spv, eviction_spv, temporal_spv, resolve_spv, compaction_spv, transport_spv: a user's shaders, as
  // VulkanFilter takes them. The device must outlive the backend.
  explicit VulkanBackend(VulkanDevice& device, const std::string& accumulate_spv = "",
                         const std::string& eviction_spv = "", const std::string& temporal_spv = "",
                         const std::string& resolve_spv = "", const std::string& compaction_spv = "",
                         const std::string& transport_spv = "")
      : filter_(device, accumulate_spv, eviction_spv, temporal_spv, resolve_spv, compaction_spv, transport_spv) {}
  std::string Name() const override { return "vulkan"; }
  const HashedRun* LastHashedRun() const override { return run_ ? &*run_ : nullptr; }
  // The last frame's run: the table after it, and its records' keys and placements. Only after a frame.
  const VulkanRun& run() const { return *run_; }
  FrameTimings LastFrameTimings() const override {
    if (!run_) return {};
    const VulkanTimings& t = run_->timings;
    return {.transport_ms = t.transport_ms,
            .keys_ms = std::nullopt,  // computed in the accumulate pass
            .accumulate_ms = t.accumulate_ms,
            .level_seed_ms = t.level_seed_ms,
            .compaction_ms = t.compaction_ms,
            .settle_ms = t.settle_ms,
            .temporal_ms = t.temporal_ms,
            .eviction_ms = t.eviction_ms,
            .resolve_ms = t.resolve_ms,
            .transfer_ms = t.UploadMs() + t.ReadBackMs()};
  }

 protected:
  const Image& FilterFrameInto(const RecordBatch& batch, const FilterConfig& config, std::uint32_t index) override {
    const FrameEffects effects = PlanFrameEffects(config, index);
    run_ = filter_.Run(batch, config, index > 0, &effects);
    return run_->image;
  }
  void ForgetTable() override { run_.reset(); }

 private:
  VulkanFilter filter_;
  std::optional<VulkanRun> run_;
};

}  // namespace hpsf

#endif  // HPSF_VULKAN_VULKAN_BACKEND_H
