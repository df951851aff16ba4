#include "vulkan/vulkan_objects.h"

namespace hpsf {

VulkanDevice& VulkanObjects::Device(StagingPolicy staging) {
  PolicyObjects& o = objects_[int(staging)];
  if (!o.device) o.device = std::make_unique<VulkanDevice>("", staging);
  return *o.device;
}

KeyPass& VulkanObjects::KeyPassOn(StagingPolicy staging) {
  PolicyObjects& o = objects_[int(staging)];
  if (!o.key_pass) o.key_pass = std::make_unique<KeyPass>(Device(staging));
  return *o.key_pass;
}

VulkanFilter& VulkanObjects::FilterOn(StagingPolicy staging) {
  PolicyObjects& o = objects_[int(staging)];
  if (!o.filter) o.filter = std::make_unique<VulkanFilter>(Device(staging));
  return *o.filter;
}

void VulkanObjects::Release() {
  for (PolicyObjects& o : objects_) {
    o.filter.reset();
    o.key_pass.reset();
    o.device.reset();
  }
}

}  // namespace hpsf
