// fixed_point.comp on a Vulkan device: core/shared/fixed_point.h's conversion of a batch of floats, read back
// so tests hold the device's rounding to the C++ result.
#ifndef HPSF_VULKAN_FIXED_POINT_PASS_H
#define HPSF_VULKAN_FIXED_POINT_PASS_H

#include <cstdint>
#include <span>
#include <vector>

#include "vulkan/vulkan_device.h"

namespace hpsf {

// round_half_to_even(value * 2^fraction_bits) for each value, on the device; fraction_bits in [-126, 126].
std::vector<std::uint64_t> ToFixedPointOnDevice(VulkanDevice& device, std::span<const float> values, int fraction_bits);

}  // namespace hpsf

#endif  // HPSF_VULKAN_FIXED_POINT_PASS_H
