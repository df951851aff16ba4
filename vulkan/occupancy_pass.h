// occupancy.comp on a Vulkan device: the HashCache's occupancy of one level (core/occupancy.h holds the reference's),
// the triangles' cells marked by atomicOr into the bit field and counted by popcount and one atomic add, read back.
#ifndef HPSF_VULKAN_OCCUPANCY_PASS_H
#define HPSF_VULKAN_OCCUPANCY_PASS_H

#include <cstdint>
#include <span>

#include "core/occupancy.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

struct DeviceOccupancy {
  OccupancyLevel field;
  std::uint64_t counted = 0;  // the device's count: the field's popcount
};

// The cells of `level` that the triangles meet, on the device.
DeviceOccupancy VoxelizeOnDevice(VulkanDevice& device, const shared::OccupancyGrid& grid,
                                 std::span<const OccupancyTriangle> triangles, int level = 0);

}  // namespace hpsf

#endif  // HPSF_VULKAN_OCCUPANCY_PASS_H
