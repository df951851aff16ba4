#include "property_tests/vulkan_test_devices.h"

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace hpsf::testing {
namespace {

struct PolicyObjects {
  std::unique_ptr<VulkanDevice> device;
  std::unique_ptr<KeyPass> key_pass;
  std::unique_ptr<VulkanFilter> filter;
};

PolicyObjects objects[3];  // by StagingPolicy

class ReleaseVulkanObjects : public ::testing::Environment {
 public:
  void TearDown() override {
    for (PolicyObjects& o : objects) {  // passes and filters before their device
      o.filter.reset();
      o.key_pass.reset();
      o.device.reset();
    }
  }
};

[[maybe_unused]] ::testing::Environment* const release = ::testing::AddGlobalTestEnvironment(new ReleaseVulkanObjects);

PolicyObjects& For(StagingPolicy staging) {
  PolicyObjects& o = objects[int(staging)];
  if (!o.device) {
    try {
      o.device = std::make_unique<VulkanDevice>("", staging);
    } catch (const VulkanUnavailable& e) {
      throw std::runtime_error(std::string("Vulkan is required for this test: ") + e.what());
    }
    std::printf("Vulkan tests with --vk-staging %s on %s\n", ToString(staging), o.device->info().ToString().c_str());
  }
  return o;
}

}  // namespace

VulkanDevice& TestDevice(StagingPolicy staging) { return *For(staging).device; }

KeyPass& TestKeyPass(StagingPolicy staging) {
  PolicyObjects& o = For(staging);
  if (!o.key_pass) o.key_pass = std::make_unique<KeyPass>(*o.device);
  return *o.key_pass;
}

VulkanFilter& TestFilter(StagingPolicy staging) {
  PolicyObjects& o = For(staging);
  if (!o.filter) o.filter = std::make_unique<VulkanFilter>(*o.device);
  return *o.filter;
}

}  // namespace hpsf::testing
