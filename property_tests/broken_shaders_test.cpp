// The broken accumulate shaders (vulkan/CMakeLists.txt: accumulate.glsl with one HPSF_DEFECT_* switch each, run
// through --accumulate-spv's path) on inputs constructed to reach their defect, as broken_kernels_test does for
// the emulator. The cells are searched by their keys, so each defect is reached whatever the hashes, the jitter's
// random numbers or the key path become: no test here depends on a scene whose keys happen to collide. On
// lavapipe a subgroup's lanes run in lockstep, so D9 and D13 race on every run; each input is also run through
// the correct shader, which must pass.
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/filter_config.h"
#include "property_tests/constructed_cells.h"
#include "property_tests/vulkan_test_devices.h"
#include "verifier/checker/table_checker.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf {
namespace {

using testing::BatchOfCells;
using testing::ConstructedConfig;
using testing::FindCell;

std::string VariantPath(const std::string& variant) {
  return std::string(HPSF_SHADER_VARIANT_DIR).append("/accumulate_").append(variant).append(".spv");
}

std::vector<TableViolation> RunVariant(const std::string& variant, const RecordBatch& batch,
                                       const FilterConfig& config) {
  VulkanFilter filter(testing::TestDevice(StagingPolicy::kNever), VariantPath(variant));
  const VulkanRun run = filter.Run(batch, config);
  return CheckTable({run.table, batch.records, run.keys, run.placements});
}

// The correct shader passes; the broken one is caught by the table checker.
void ExpectCaught(const std::string& variant, const RecordBatch& batch, const FilterConfig& config) {
  const std::vector<TableViolation> correct = RunVariant("correct", batch, config);
  EXPECT_TRUE(correct.empty()) << "the correct shader failed: " << correct.front().ToString();
  const std::vector<TableViolation> broken = RunVariant(variant, batch, config);
  ASSERT_FALSE(broken.empty()) << variant << " escaped the table checker";
  std::printf("%s caught: %s\n", variant.c_str(), broken.front().ToString().c_str());
}

TEST(BrokenShaders, D2AddingAgainAfterAMatchIsCaught) {
  // One key with a free slot after its own: D2 claims that one too and adds the record twice.
  const FilterConfig config = ConstructedConfig(64, 4);
  ExpectCaught("D2", BatchOfCells({{1, 2, 3}, {1, 2, 3}, {9, 9, 9}}), config);
}

TEST(BrokenShaders, D3AZeroFingerprintIsCaught) {
  // A key whose 8-bit fingerprint reduces to 0: D3 writes the empty tag as its claim.
  const FilterConfig config = ConstructedConfig(64, 4, 8);
  const glm::ivec3 zero = FindCell(config, [&](const KeyResult& k) { return testing::ReducesToZero(config, k); });
  ExpectCaught("D3", BatchOfCells({zero, zero}), config);
}

TEST(BrokenShaders, D8AClampedProbeIsCaught) {
  // Two keys at slot0 = capacity - 1: the second must wrap to slot 0; D8 stays at the last slot.
  const FilterConfig config = ConstructedConfig(64, 4);
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 63u; });
  const glm::ivec3 b = FindCell(
      config, [](const KeyResult& k) { return k.slot0 == 63u; }, a.x + 1);
  ExpectCaught("D8", BatchOfCells({a, b}), config);
}

TEST(BrokenShaders, D9LostUpdatesInOneSubgroupAreCaught) {
  // Eight records of one cell side by side: one subgroup's lanes load the same sum and store in turn.
  const FilterConfig config = ConstructedConfig(64, 4);
  ExpectCaught("D9", BatchOfCells(std::vector<glm::ivec3>(8, glm::ivec3(5, 5, 5))), config);
}

TEST(BrokenShaders, D13TwoKeysRacingForOneEmptySlotAreCaught) {
  // Two keys with one slot0 in neighbouring lanes: both see the slot empty and both store their tag.
  const FilterConfig config = ConstructedConfig(64, 4);
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 17u; });
  const glm::ivec3 b = FindCell(
      config, [](const KeyResult& k) { return k.slot0 == 17u; }, a.x + 1);
  ExpectCaught("D13", BatchOfCells({a, b, a, b}), config);
}

}  // namespace
}  // namespace hpsf
