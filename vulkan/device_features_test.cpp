#include "vulkan/device_features.h"

#include <gtest/gtest.h>

namespace hpsf {
namespace {

DeviceFeatures Complete() {
  DeviceFeatures f;
  f.api_version = (1u << 22) | (3u << 12);
  f.shader_int64 = f.buffer_int64_atomics = f.buffer_float32_atomic_add = f.robust_buffer_access = true;
  f.rounding_mode_rte_float32 = f.signed_zero_inf_nan_preserve_float32 = f.timestamp_compute = true;
  f.shader_float64 = f.rounding_mode_rte_float64 = f.signed_zero_inf_nan_preserve_float64 = true;
  return f;
}

TEST(DeviceFeatures, ACompleteDeviceQualifies) { EXPECT_TRUE(MissingRequiredFeatures(Complete()).empty()); }

TEST(DeviceFeatures, EachMissingFeatureIsNamed) {
  const std::pair<bool DeviceFeatures::*, const char*> cases[] = {
      {&DeviceFeatures::shader_int64, "shaderInt64"},
      {&DeviceFeatures::robust_buffer_access, "robustBufferAccess"},
      {&DeviceFeatures::buffer_int64_atomics, "shaderBufferInt64Atomics"},
      {&DeviceFeatures::buffer_float32_atomic_add, "shaderBufferFloat32AtomicAdd"},
      {&DeviceFeatures::rounding_mode_rte_float32, "shaderRoundingModeRTEFloat32"},
      {&DeviceFeatures::signed_zero_inf_nan_preserve_float32, "shaderSignedZeroInfNanPreserveFloat32"},
      {&DeviceFeatures::shader_float64, "shaderFloat64"},
      {&DeviceFeatures::rounding_mode_rte_float64, "shaderRoundingModeRTEFloat64"},
      {&DeviceFeatures::signed_zero_inf_nan_preserve_float64, "shaderSignedZeroInfNanPreserveFloat64"},
      {&DeviceFeatures::timestamp_compute, "timestampComputeAndGraphics"},
  };
  for (const auto& [member, name] : cases) {
    DeviceFeatures f = Complete();
    f.*member = false;
    const auto missing = MissingRequiredFeatures(f);
    ASSERT_EQ(missing.size(), 1u) << name;
    EXPECT_EQ(missing[0].rfind(name, 0), 0u) << missing[0];
  }
  DeviceFeatures old = Complete();
  old.api_version = (1u << 22) | (1u << 12);
  ASSERT_EQ(MissingRequiredFeatures(old).size(), 1u);
  EXPECT_NE(MissingRequiredFeatures(old)[0].find("Vulkan 1.2"), std::string::npos);
}

}  // namespace
}  // namespace hpsf
