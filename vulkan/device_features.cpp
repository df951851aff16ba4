#include "vulkan/device_features.h"

namespace hpsf {
namespace {

constexpr std::uint32_t kRequiredApiVersion = (1u << 22) | (2u << 12);  // VK_API_VERSION_1_2

}  // namespace

std::vector<std::string> MissingRequiredFeatures(const DeviceFeatures& f) {
  std::vector<std::string> missing;
  if (f.api_version < kRequiredApiVersion) missing.push_back("Vulkan 1.2 (float controls and 64-bit atomics)");
  if (!f.rounding_mode_rte_float32)
    missing.push_back("shaderRoundingModeRTEFloat32 (fp32 round-to-nearest-even for exact keys)");
  if (!f.signed_zero_inf_nan_preserve_float32) {
    missing.push_back("shaderSignedZeroInfNanPreserveFloat32 (fp32 signed zeros in keys and normal buckets)");
  }
  if (!f.shader_int64) missing.push_back("shaderInt64 (fixed64 accumulation)");
  if (!f.robust_buffer_access) {
    missing.push_back("robustBufferAccess (a team's shader indexing past a buffer must not write the host's memory)");
  }
  if (!f.buffer_int64_atomics) missing.push_back("shaderBufferInt64Atomics (fixed64 accumulation)");
  if (!f.buffer_float32_atomic_add) missing.push_back("shaderBufferFloat32AtomicAdd (float32 accumulation)");
  if (!f.shader_float64) missing.push_back("shaderFloat64 (the resolve pass in double, as the reference)");
  if (!f.rounding_mode_rte_float64) missing.push_back("shaderRoundingModeRTEFloat64 (resolve rounds as the reference)");
  if (!f.signed_zero_inf_nan_preserve_float64)
    missing.push_back("shaderSignedZeroInfNanPreserveFloat64 (resolve keeps signed zeros)");
  if (!f.timestamp_compute) missing.push_back("timestampComputeAndGraphics (timings)");
  return missing;
}

}  // namespace hpsf
