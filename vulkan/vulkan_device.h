// The Vulkan device hpsf runs on: a real GPU when present, else lavapipe, or the one --vk-device names. Opening
// it checks every required feature up front; a missing device or feature throws VulkanUnavailable naming it.
// Vulkan headers stay out of this header: they are slow to compile, so only a few translation units see them.
#ifndef HPSF_VULKAN_VULKAN_DEVICE_H
#define HPSF_VULKAN_VULKAN_DEVICE_H

#include <memory>
#include <stdexcept>
#include <string>

#include "vulkan/device_features.h"

namespace hpsf {

// No usable Vulkan device; the command line reports the message and exits with code 3.
class VulkanUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Where the kernels' buffers live and how the host reaches them. The kernels always use DEVICE_LOCAL memory;
// `staged` moves data through host-cached staging buffers with copy commands (a discrete GPU, whose host-visible
// device memory is uncached), otherwise the host maps the kernels' buffers (lavapipe, integrated GPUs). kAuto
// stages unless a memory type is DEVICE_LOCAL, HOST_VISIBLE and HOST_CACHED at once.
enum class StagingPolicy { kAuto, kAlways, kNever };
StagingPolicy ParseStagingPolicy(const std::string& text);  // ConfigError naming --vk-staging
const char* ToString(StagingPolicy policy);

struct VulkanDeviceInfo {
  std::string name;         // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string type;         // discrete, integrated, virtual, cpu, other
  std::string driver_name;  // e.g. "llvmpipe"
  std::string driver_info;  // e.g. "Mesa 22.3.6 (LLVM 15.0.6)"
  std::string api_version;  // e.g. "1.3.230"
  std::uint32_t subgroup_size = 0;
  bool staged = false;  // the host reaches the kernels' buffers through staging copies
  std::string memory;   // the memory types chosen, for reports
  DeviceFeatures features;
  std::string ToString() const;
};

class VulkanDevice {
 public:
  // name_filter: a case-insensitive substring of the device name; empty picks the best device.
  explicit VulkanDevice(const std::string& name_filter = "", StagingPolicy staging = StagingPolicy::kAuto);
  ~VulkanDevice();
  VulkanDevice(const VulkanDevice&) = delete;
  VulkanDevice& operator=(const VulkanDevice&) = delete;

  const VulkanDeviceInfo& info() const;

  struct Impl;  // vulkan/vulkan_internal.h
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace hpsf

#endif  // HPSF_VULKAN_VULKAN_DEVICE_H
