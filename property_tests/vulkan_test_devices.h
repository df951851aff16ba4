// The Vulkan objects a test binary shares (vulkan/vulkan_objects.h), one set per staging policy, released by a
// GoogleTest environment when the tests end, before main returns (static destruction of a device crashed
// NVIDIA's driver). No device fails the test that asked: Vulkan tests never skip.
#ifndef HPSF_PROPERTY_TESTS_VULKAN_TEST_DEVICES_H
#define HPSF_PROPERTY_TESTS_VULKAN_TEST_DEVICES_H

#include "vulkan/key_pass.h"
#include "vulkan/vulkan_device.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf::testing {

// The two ways the host reaches the kernels' buffers; every Vulkan property runs over both.
inline constexpr StagingPolicy kStagingPolicies[] = {StagingPolicy::kNever, StagingPolicy::kAlways};

VulkanDevice& TestDevice(StagingPolicy staging);
KeyPass& TestKeyPass(StagingPolicy staging);
VulkanFilter& TestFilter(StagingPolicy staging);

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_VULKAN_TEST_DEVICES_H
