// SumsAccumulation on hpsf's own shaders, whose binding 3 is known: the accumulate shaders' sums give their mode;
// shaders whose binding 3 is something else, or absent, and bytes that are not SPIR-V are refused, naming the file.
#include "vulkan/spirv_reflection.h"

#include <gtest/gtest.h>

#include "accumulate_fixed64_spv.h"
#include "accumulate_float32_spv.h"
#include "accumulate_packed_decimal_spv.h"
#include "core/error.h"
#include "eviction_spv.h"
#include "keys_spv.h"
#include "resolve_fixed64_spv.h"
#include "resolve_float32_spv.h"
#include "resolve_packed_decimal_spv.h"
#include "temporal_spv.h"
#include "transport_spv.h"

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
  EXPECT_EQ(SumsAccumulation(accumulate_packed_decimal_spv, "a.spv"), Accumulation::kPackedDecimal);
}

// A resolve shader's sums are binding 1 (--resolve-spv).
TEST(SpirvReflection, TheResolveShadersDeclareTheirModeAtBindingOne) {
  EXPECT_EQ(SumsAccumulation(resolve_fixed64_spv, "r.spv", 1), Accumulation::kFixed64);
  EXPECT_EQ(SumsAccumulation(resolve_float32_spv, "r.spv", 1), Accumulation::kFloat32);
  EXPECT_EQ(SumsAccumulation(resolve_packed_decimal_spv, "r.spv", 1), Accumulation::kPackedDecimal);
  try {
    SumsAccumulation(keys_spv, "k.spv", 1);
    ADD_FAILURE() << "keys.comp's binding 1 taken for sums";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "k.spv: binding 1 (sums) holds a vector of 4 uint; the stable buffer interface takes uint64_t "
              "(fixed64), float (float32) or uint (packed-decimal)");
  }
}

TEST(SpirvReflection, OtherBindingsAndBytesAreRefused) {
  // Two element types at one binding (eviction.comp's counts, viewed as 64-bit counts and 32-bit count words).
  try {
    SumsAccumulation(eviction_spv, "e.spv", 2);
    ADD_FAILURE() << "two views taken for one mode";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "e.spv: binding 2 (sums) holds uint and uint64_t; the stable buffer interface takes uint64_t "
              "(fixed64), float (float32) or uint (packed-decimal)");
  }
  // Reflection reads the type, not the name: eviction.comp's binding 3 (last_seen, uint) reads as packed-decimal
  // sums. A shader that is not an accumulate is caught by its run, not here.
  EXPECT_EQ(SumsAccumulation(eviction_spv, "e.spv"), Accumulation::kPackedDecimal);
  EXPECT_EQ(Refusal(keys_spv),
            "x.spv: declares no storage buffer at binding 3 (the sums of the stable buffer interface)");
  const std::uint32_t not_spirv[] = {0x07230203u, 1u, 2u};
  EXPECT_EQ(Refusal(not_spirv).rfind("x.spv: the SPIR-V does not reflect: ", 0), 0u) << Refusal(not_spirv);
}

// A 32-bit view of the counts binding used: packed-decimal's count words. eviction.comp (binding 2), temporal.comp
// (binding 1) and transport.comp (binding 5) use both views (by a push constant); a resolve's counts are binding 2,
// 64-bit or count words by its mode.
TEST(SpirvReflection, APassShaderReadsCountWordsOnlyThroughA32BitView) {
  EXPECT_TRUE(ReadsCountWords(eviction_spv, "e.spv", kEvictionCountsBinding));
  EXPECT_TRUE(ReadsCountWords(temporal_spv, "t.spv", kTemporalCountsBinding));
  EXPECT_TRUE(ReadsCountWords(transport_spv, "p.spv", kTransportCountsBinding));
  EXPECT_TRUE(ReadsCountWords(resolve_packed_decimal_spv, "r.spv", 2));
  EXPECT_FALSE(ReadsCountWords(resolve_fixed64_spv, "r.spv", 2));
}

}  // namespace
}  // namespace hpsf
