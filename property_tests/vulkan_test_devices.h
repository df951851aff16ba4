// The Vulkan objects a test binary shares, one set per staging policy, opened on first use and released by a
// GoogleTest environment when the tests end, before main returns: a device destroyed during static destruction
// crashed NVIDIA's driver after every test had passed. No device fails the test that asked: Vulkan tests never skip.
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
