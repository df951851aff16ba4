#include "property_tests/vulkan_test_devices.h"

#include <cstdio>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "vulkan/vulkan_objects.h"

namespace hpsf::testing {
namespace {

VulkanObjects objects;

class ReleaseVulkanObjects : public ::testing::Environment {
 public:
  void TearDown() override { objects.Release(); }
};

[[maybe_unused]] ::testing::Environment* const release = ::testing::AddGlobalTestEnvironment(new ReleaseVulkanObjects);

// Opens the policy's device, or fails the test that asked.
VulkanDevice& Opened(StagingPolicy staging) {
  static bool announced[3] = {false, false, false};
  try {
    VulkanDevice& device = objects.Device(staging);
    if (!announced[int(staging)]) {
      announced[int(staging)] = true;
      std::printf("Vulkan tests with --vk-staging %s on %s\n", ToString(staging), device.info().ToString().c_str());
    }
    return device;
  } catch (const VulkanUnavailable& e) {
    throw std::runtime_error(std::string("Vulkan is required for this test: ") + e.what());
  }
}

}  // namespace

VulkanDevice& TestDevice(StagingPolicy staging) { return Opened(staging); }

KeyPass& TestKeyPass(StagingPolicy staging) {
  Opened(staging);
  return objects.KeyPassOn(staging);
}

VulkanFilter& TestFilter(StagingPolicy staging) {
  Opened(staging);
  return objects.FilterOn(staging);
}

}  // namespace hpsf::testing
