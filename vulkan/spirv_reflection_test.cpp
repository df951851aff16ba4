// SumsAccumulation on hpsf's own shaders, whose binding 3 is known: the accumulate shaders' sums give their mode;
// shaders whose binding 3 is something else, or absent, and bytes that are not SPIR-V are refused, naming the file.
#include "vulkan/spirv_reflection.h"

#include <gtest/gtest.h>

#include "accumulate_fixed64_spv.h"
#include "accumulate_float32_spv.h"
#include "core/error.h"
#include "eviction_spv.h"
#include "keys_spv.h"
#include "resolve_fixed64_spv.h"
#include "resolve_float32_spv.h"
#include "temporal_spv.h"

namespace hpsf {
namespace {

std::string Refusal(std::span<const std::uint32_t> spirv) {
  try {
    SumsAccumulation(spirv, "x.spv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SpirvReflection, TheAccumulateShadersDeclareTheirMode) {
  EXPECT_EQ(SumsAccumulation(accumulate_fixed64_spv, "a.spv"), Accumulation::kFixed64);
  EXPECT_EQ(SumsAccumulation(accumulate_float32_spv, "a.spv"), Accumulation::kFloat32);
  // temporal.comp's binding 3 is a uint64_t array too: reflection reads the type, not the name.
  EXPECT_EQ(SumsAccumulation(temporal_spv, "t.spv"), Accumulation::kFixed64);
}

// A resolve shader's sums are binding 1 (--resolve-spv).
TEST(SpirvReflection, TheResolveShadersDeclareTheirModeAtBindingOne) {
  EXPECT_EQ(SumsAccumulation(resolve_fixed64_spv, "r.spv", 1), Accumulation::kFixed64);
  EXPECT_EQ(SumsAccumulation(resolve_float32_spv, "r.spv", 1), Accumulation::kFloat32);
  try {
    SumsAccumulation(keys_spv, "k.spv", 1);
    ADD_FAILURE() << "keys.comp's binding 1 taken for sums";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "k.spv: binding 1 (sums) holds uint; the stable buffer interface takes uint64_t "
              "(fixed64) or float (float32)");
  }
}

TEST(SpirvReflection, OtherBindingsAndBytesAreRefused) {
  EXPECT_EQ(Refusal(eviction_spv),
            "x.spv: binding 3 (sums) holds uint; the stable buffer interface takes uint64_t "
            "(fixed64) or float (float32)");
  EXPECT_EQ(Refusal(keys_spv),
            "x.spv: declares no storage buffer at binding 3 (the sums of the stable buffer interface)");
  const std::uint32_t not_spirv[] = {0x07230203u, 1u, 2u};
  EXPECT_EQ(Refusal(not_spirv).rfind("x.spv: the SPIR-V does not reflect: ", 0), 0u) << Refusal(not_spirv);
}

}  // namespace
}  // namespace hpsf
