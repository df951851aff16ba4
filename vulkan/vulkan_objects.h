// The Vulkan objects a long-lived program shares (a test binary, a benchmark), one set per staging policy,
// opened on first use. Release() must run before main returns: a device destroyed during static destruction
// crashed NVIDIA's driver at exit, after every test had passed.
#ifndef HPSF_VULKAN_VULKAN_OBJECTS_H
#define HPSF_VULKAN_VULKAN_OBJECTS_H

#include <memory>

#include "vulkan/key_pass.h"
#include "vulkan/vulkan_device.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf {

class VulkanObjects {
 public:
  // Each throws VulkanUnavailable when no device opens.
  VulkanDevice& Device(StagingPolicy staging);
  KeyPass& KeyPassOn(StagingPolicy staging);
  VulkanFilter& FilterOn(StagingPolicy staging);
  // Passes and filters, then their devices.
  void Release();

 private:
  struct PolicyObjects {
    std::unique_ptr<VulkanDevice> device;
    std::unique_ptr<KeyPass> key_pass;
    std::unique_ptr<VulkanFilter> filter;
  };
  PolicyObjects objects_[3];  // by StagingPolicy
};

}  // namespace hpsf

#endif  // HPSF_VULKAN_VULKAN_OBJECTS_H
