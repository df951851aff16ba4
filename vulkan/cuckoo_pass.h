// cuckoo.comp on a Vulkan device: a HashCache level's cuckoo map built from its keys (core/cuckoo_map.h holds the
// reference's construction), attempt after attempt with Roth's growth as BuildCuckooMap, each attempt's map read back.
#ifndef HPSF_VULKAN_CUCKOO_PASS_H
#define HPSF_VULKAN_CUCKOO_PASS_H

#include <cstdint>
#include <span>

#include "core/cuckoo_map.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

CuckooBuild BuildCuckooMapOnDevice(VulkanDevice& device, std::span<const std::uint32_t> keys,
                                   const CuckooBuildOptions& options);

}  // namespace hpsf

#endif  // HPSF_VULKAN_CUCKOO_PASS_H
