// Level 1 of the cross-check, on lavapipe here and on a real GPU where there is one: every output word of
// keys.comp equals the C++ result of the same shared code, bit for bit, with no exceptions, whether the host
// maps the device's buffers or moves data through staging buffers.
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/input_check.h"
#include "core/key_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "verifier/generators/record_generators.h"

namespace hpsf::testing {
namespace {

// Writes the failing case where a person can replay it: config and records, floats in round-trip decimal.
std::string WriteRepro(const KeyCase& key_case, std::uint32_t seed, const Record& record, const KeyResult& cpu,
                       const KeyResult& gpu) {
  const std::string path = "key_identity_failure_" + std::to_string(seed) + ".txt";
  std::ofstream out(path);
  out << "generator seed: " << seed << "\n"
      << key_case.ToString() << "\n"
      << ToString(record) << "\ncpu: " << ToString(cpu) << "\ngpu: " << ToString(gpu) << "\n";
  return path;
}

void CheckBatchIsBitIdentical(const KeyCase& key_case, std::uint32_t seed, const std::vector<Record>& records) {
  // Non-finite inputs are rejected on the host before any shader sees them; the generators must not make any.
  for (const Record& r : records) RC_ASSERT(CheckRecordInputs(r) == InputVerdict::kAccepted);
  const KeyParams params = key_case.Params(static_cast<std::uint32_t>(records.size()));
  const std::vector<KeyResult> cpu = ComputeKeys(records, params);
  for (const StagingPolicy staging : kStagingPolicies) {
    const std::vector<KeyResult> gpu = TestKeyPass(staging).Run(records, params);
    RC_ASSERT(gpu.size() == cpu.size());
    for (std::size_t i = 0; i < records.size(); ++i) {
      const auto c = KeyResultWords(cpu[i]), g = KeyResultWords(gpu[i]);
      if (c == g) continue;
      int word = 0;
      while (c[word] == g[word]) ++word;
      const std::string repro = WriteRepro(key_case, seed, records[i], cpu[i], gpu[i]);
      RC_FAIL("record " + std::to_string(i) + ": " + KeyResultWordName(word) + " differs (cpu " +
              std::to_string(c[word]) + ", gpu " + std::to_string(g[word]) + ", --vk-staging " + ToString(staging) +
              "); generator seed " + std::to_string(seed) + "; written to " + repro + "\n" + ToString(records[i]) +
              "\ncpu " + ToString(cpu[i]) + "\ngpu " + ToString(gpu[i]) + "\n" + key_case.ToString());
    }
  }
}

void CheckKind(RecordKind kind) {
  const std::uint32_t seed = *rc::gen::arbitrary<std::uint32_t>();
  const std::size_t count = *rc::gen::inRange<std::size_t>(1, 600);
  RecordGenerator generator(seed);
  const KeyCase key_case = generator.Case();
  RC_TAG(key_case.config.lod ? "lod" : "fixed-cell");
  CheckBatchIsBitIdentical(key_case, seed, generator.Batch(kind, key_case.Params(0), count));
}

RC_GTEST_PROP(KeyIdentity, UniformRecords, ()) { CheckKind(RecordKind::kUniform); }
RC_GTEST_PROP(KeyIdentity, WithinUlpsOfACellBoundary, ()) { CheckKind(RecordKind::kCellBoundary); }
RC_GTEST_PROP(KeyIdentity, WithinUlpsOfALevelBoundary, ()) { CheckKind(RecordKind::kLevelBoundary); }
RC_GTEST_PROP(KeyIdentity, FarFromTheOriginAt1e5, ()) { CheckKind(RecordKind::kFar1e5); }
RC_GTEST_PROP(KeyIdentity, FarFromTheOriginAt1e7, ()) { CheckKind(RecordKind::kFar1e7); }
RC_GTEST_PROP(KeyIdentity, NormalsWithSignedZeroComponents, ()) { CheckKind(RecordKind::kSignedZeroNormal); }

RC_GTEST_PROP(KeyIdentity, TinyAndDenormalCellSizesAndUnkeyables, ()) {
  const std::uint32_t seed = *rc::gen::arbitrary<std::uint32_t>();
  RecordGenerator generator(seed);
  KeyCase key_case = generator.Case();
  // Level of detail off with a cell size from 2^-126 up to 1e-20 (most records unkeyable), or on with a
  // footprint whose product with d is denormal, so the level is clamped to its minimum.
  key_case.config.lod = *rc::gen::arbitrary<bool>();
  key_case.config.cell_size = std::ldexp(1.0f, *rc::gen::inRange(-126, -66));
  key_case.footprint_scale = *rc::gen::element(0.0f, 1e-45f, 1e-40f, 1e-38f, 1e-36f);
  key_case.config.level_min = -126;
  CheckBatchIsBitIdentical(key_case, seed, generator.MixedBatch(key_case.Params(0), 500));
}

TEST(KeyIdentity, OneMillionMixedRecordsAcrossTwentyConfigs) {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    RecordGenerator generator(seed);
    const KeyCase key_case = generator.Case();
    const std::vector<Record> records = generator.MixedBatch(key_case.Params(0), 50000);
    const KeyParams params = key_case.Params(static_cast<std::uint32_t>(records.size()));
    for (const Record& r : records) ASSERT_EQ(CheckRecordInputs(r), InputVerdict::kAccepted) << ToString(r);
    const std::vector<KeyResult> cpu = ComputeKeys(records, params);
    for (const StagingPolicy staging : kStagingPolicies) {
      const std::vector<KeyResult> gpu = TestKeyPass(staging).Run(records, params);
      std::size_t differing = 0;
      for (std::size_t i = 0; i < records.size(); ++i) differing += KeyResultWords(cpu[i]) != KeyResultWords(gpu[i]);
      EXPECT_EQ(differing, 0u) << "generator seed " << seed << ", --vk-staging " << ToString(staging) << " "
                               << key_case.ToString();
    }
  }
}

}  // namespace
}  // namespace hpsf::testing
