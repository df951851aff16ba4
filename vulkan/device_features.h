// The device capabilities hpsf needs, as plain data, and the check that names what is missing. Kept free of
// Vulkan headers so the check is unit-tested without a device.
#ifndef HPSF_VULKAN_DEVICE_FEATURES_H
#define HPSF_VULKAN_DEVICE_FEATURES_H

#include <cstdint>
#include <string>
#include <vector>

namespace hpsf {

struct DeviceFeatures {
  std::uint32_t api_version = 0;
  bool shader_int64 = false;
  bool robust_buffer_access = false;
  bool buffer_int64_atomics = false;
  bool buffer_float32_atomic_add = false;
  bool rounding_mode_rte_float32 = false;
  bool signed_zero_inf_nan_preserve_float32 = false;
  bool shader_float64 = false;  // the resolve pass works in double, as core/resolve
  bool rounding_mode_rte_float64 = false;
  bool signed_zero_inf_nan_preserve_float64 = false;
  bool timestamp_compute = false;
};

// Each missing requirement as "<Vulkan name> (<why hpsf needs it>)"; empty when the device qualifies.
std::vector<std::string> MissingRequiredFeatures(const DeviceFeatures& features);

}  // namespace hpsf

#endif  // HPSF_VULKAN_DEVICE_FEATURES_H
