// Records a shader must never see, through every backend: NaN, +Inf and -Inf in each component of each float
// field, and a negative value in each field the checks call a radiance or a length. Each is rejected on the host
// and counted, never placed in a table, its pixel stays finite, and the cross-check holds with all backends,
// the Vulkan host mapping its buffers or staging them.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/input_check.h"
#include "emulated/emulated_filter.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_filter.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf::testing {
namespace {

struct Poison {
  glm::vec4 Record::*field;
  const char* name;
  int component;
  float value;
  InputVerdict verdict;
};

std::vector<Poison> Poisons() {
  const std::pair<glm::vec4 Record::*, const char*> fields[] = {
      {&Record::position, "position"},     {&Record::normal, "normal"},
      {&Record::tangent, "tangent"},       {&Record::bitangent, "bitangent"},
      {&Record::previous, "previous"},     {&Record::contribution, "contribution"},
      {&Record::throughput, "throughput"}, {&Record::radiance_before, "radiance_before"}};
  std::vector<Poison> poisons;
  for (const auto& [field, name] : fields) {
    for (int c = 0; c < 4; ++c) {
      for (const float bad : {std::numeric_limits<float>::quiet_NaN(), INFINITY, -INFINITY}) {
        poisons.push_back({field, name, c, bad, InputVerdict::kNonFinite});
      }
    }
  }
  // Negative radiance and path length (position.w is d_prefix); negative coordinates are fine.
  for (int c = 0; c < 4; ++c) {
    poisons.push_back({&Record::radiance_before, "radiance_before", c, -1.0f, InputVerdict::kNegative});
    poisons.push_back({&Record::contribution, "contribution", c, -0.5f, InputVerdict::kNegative});
    poisons.push_back({&Record::throughput, "throughput", c, -2.0f, InputVerdict::kNegative});
  }
  poisons.push_back({&Record::position, "position", 3, -1.0f, InputVerdict::kNegative});
  return poisons;
}

struct PoisonedBatch {
  RecordBatch batch;
  std::vector<std::size_t> poisoned;  // record indices, one per poison
  std::uint64_t non_finite = 0, negative = 0;
};

PoisonedBatch MakePoisonedBatch() {
  PoisonedBatch p;
  p.batch = TracedBatch("cornell", 16, 2);
  std::size_t next = 0;
  for (const Poison& poison : Poisons()) {
    while (!shared::RecordHasVertex(p.batch.records[next])) ++next;  // every field is checked on a vertex record
    Record& r = p.batch.records[next];
    EXPECT_EQ(CheckRecordInputs(r), InputVerdict::kAccepted);
    (r.*poison.field)[poison.component] = poison.value;
    EXPECT_EQ(CheckRecordInputs(r), poison.verdict) << poison.name << "[" << poison.component << "] = " << poison.value;
    (poison.verdict == InputVerdict::kNonFinite ? p.non_finite : p.negative) += 1;
    p.poisoned.push_back(next);
    next += 3;  // spread over pixels
  }
  return p;
}

void ExpectFinite(const Image& image, const std::string& backend) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(image.pixels[i][c])) << backend << " pixel " << i;
  }
}

void ExpectRejected(const PoisonedBatch& p, const HashedRun& run, const std::string& backend) {
  for (std::size_t i : p.poisoned)
    EXPECT_EQ(run.placements[i], kNotPlaced) << backend << ": record " << i << " was placed";
  EXPECT_TRUE(CheckTable({run.table, p.batch.records, run.keys, run.placements}).empty()) << backend;
  ExpectFinite(run.image, backend);
}

TEST(RejectedInputs, EveryPoisonedFieldIsRejectedCountedAndKeptOutOfEveryTable) {
  const PoisonedBatch p = MakePoisonedBatch();
  ASSERT_EQ(p.non_finite, 96u);
  ASSERT_EQ(p.negative, 13u);
  FilterConfig config;
  config.capacity = 1u << 12;
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    config.accumulation = accumulation;
    const FilterResult reference = ReferenceFilter(p.batch, config);
    EXPECT_EQ(reference.stats.rejected_non_finite, p.non_finite);
    EXPECT_EQ(reference.stats.rejected_negative, p.negative);
    for (std::size_t i : p.poisoned) EXPECT_EQ(reference.placement[i], kNoCell);
    ExpectFinite(reference.image, "reference");

    EmulatorOptions faithful;
    faithful.mode = simt::Mode::kFaithful;
    faithful.warp_size = 8;
    ExpectRejected(p, EmulatedFilter(p.batch, config, EmulatorOptions{}), "emulated fast");
    ExpectRejected(p, EmulatedFilter(p.batch, config, faithful), "emulated faithful");
    for (const StagingPolicy staging : kStagingPolicies) {
      ExpectRejected(p, TestFilter(staging).Run(p.batch, config),
                     std::string("vulkan, --vk-staging ") + ToString(staging));
      VulkanBackendOptions vulkan;
      vulkan.staging = staging;
      const CrosscheckReport report =
          Crosscheck(p.batch, config, {"reference", "emulated", "vulkan"}, EmulatorOptions{}, Defect::kNone, vulkan);
      for (const LevelVerdict& v : report.levels) {
        EXPECT_TRUE(!v.applicable || v.passed)
            << "level " << v.level << ": " << (v.failures.empty() ? v.note : v.failures.front());
      }
    }
  }
}

}  // namespace
}  // namespace hpsf::testing
