// The table checker accepts every table the correct kernels produce, over generated batches, configs,
// schedules, warp sizes and both modes; with nothing failed or aliased the fixed64 image is the reference's,
// bit for bit. And it rejects hand-corrupted tables, one test per invariant.
#include <algorithm>
#include <functional>
#include <optional>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "emulated/emulated_filter.h"
#include "property_tests/record_generators.h"
#include "reference/reference_filter.h"
#include "tools/checks/table_checker.h"

namespace hpsf::testing {
namespace {

RecordBatch GeneratedBatch(std::uint32_t seed, std::uint32_t count) {
  RecordGenerator generator(seed);
  KeyCase key_case;
  RecordBatch batch;
  batch.width = count;
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 0.01 * (1 + seed % 50);  // cells from fine to coarse
  batch.records = generator.MixedBatch(key_case.Params(0), count);
  for (std::uint32_t i = 0; i < count; ++i) {  // one record per pixel, in order
    batch.records[i].path.x = i;
    batch.records[i].path.y = 0;
  }
  return batch;
}

std::vector<TableViolation> Check(const EmulatedRun& run, const RecordBatch& batch) {
  return CheckTable({run.table, batch.records, run.keys, run.placements});
}

bool Aliased(const EmulatedRun& run) {
  const std::vector<bool> aliased = AliasedSlots(run);
  return std::find(aliased.begin(), aliased.end(), true) != aliased.end();
}

RC_GTEST_PROP(TableChecker, AcceptsEveryTableOfTheCorrectKernels, ()) {
  const std::uint32_t seed = *rc::gen::arbitrary<std::uint32_t>();
  const RecordBatch batch = GeneratedBatch(seed, *rc::gen::inRange(1u, 400u));
  FilterConfig config;
  config.capacity = 1u << *rc::gen::inRange(2, 11);
  config.probe_limit = *rc::gen::inRange(1u, std::min(config.capacity, 16u) + 1u);
  config.fingerprint_bits = *rc::gen::inRange(8u, 33u);
  config.accumulation = *rc::gen::element(Accumulation::kFixed64, Accumulation::kFloat32);
  config.normal_in_index = *rc::gen::arbitrary<bool>();
  EmulatorOptions options;
  options.mode = *rc::gen::element(simt::Mode::kFast, simt::Mode::kFaithful);
  options.warp_size = *rc::gen::element(8u, 32u, 64u);
  options.schedule = *rc::gen::element(std::string("round-robin"), "random:" + std::to_string(seed), "pct:" + std::to_string(seed) + ":3");
  RC_TAG(options.mode == simt::Mode::kFast ? "fast" : "faithful");

  const EmulatedRun run = EmulatedFilter(batch, config, options);
  const std::vector<TableViolation> violations = Check(run, batch);
  for (const TableViolation& v : violations) RC_LOG() << v.ToString() << "\n";
  RC_ASSERT(violations.empty());

  const bool clean = run.probe_failures == 0 && !Aliased(run);
  RC_TAG(clean ? "no failure, no alias" : "failures or aliases");
  if (clean && config.accumulation == Accumulation::kFixed64) {
    const Image reference = ReferenceFilter(batch, config).image;
    RC_ASSERT(SameBits(reference, run.image));
  }
}

// A correct table to corrupt: by default crowded (300 records into 64 slots: collisions and probe failures),
// or roomy (1024 slots: empty slots too).
struct Fixture {
  explicit Fixture(std::uint32_t capacity = 64) {
    config.capacity = capacity;
    config.probe_limit = 4;
    run = EmulatedFilter(batch, config, EmulatorOptions{});
  }
  RecordBatch batch = GeneratedBatch(7, 300);
  FilterConfig config;
  EmulatedRun run;

  bool Has(TableInvariant invariant) {
    for (const TableViolation& v : Check(run, batch)) {
      if (v.invariant == invariant) return true;
    }
    return false;
  }
  std::uint32_t PlacedRecordWithProbe(std::uint32_t minimum_probe) const {
    for (std::uint32_t i = 0; i < run.placements.size(); ++i) {
      const std::uint32_t slot = run.placements[i];
      if (slot < config.capacity && ((slot - run.keys[i].slot0) & (config.capacity - 1)) >= minimum_probe) return i;
    }
    return kNotPlaced;
  }
};

TEST(TableChecker, TheFixturesAreCleanCrowdedAndRoomy) {
  Fixture crowded, roomy(1024);
  EXPECT_TRUE(Check(crowded.run, crowded.batch).empty());
  EXPECT_TRUE(Check(roomy.run, roomy.batch).empty());
  EXPECT_GT(crowded.run.probe_failures, 0u);
  EXPECT_NE(crowded.PlacedRecordWithProbe(1), kNotPlaced);
  EXPECT_NE(std::count(roomy.run.table.tags.begin(), roomy.run.table.tags.end(), kEmptyTag), 0);
}

TEST(TableChecker, RejectsAChangedTag) {
  Fixture f;
  const std::uint32_t i = f.PlacedRecordWithProbe(0);
  f.run.table.tags[f.run.placements[i]] ^= 0x1u;
  EXPECT_TRUE(f.Has(TableInvariant::kTagIsNotTheFingerprint));
}

TEST(TableChecker, RejectsASlotOutsideTheWindow) {
  Fixture f;
  const std::uint32_t i = f.PlacedRecordWithProbe(0);
  f.run.placements[i] = (f.run.keys[i].slot0 + f.config.probe_limit) & (f.config.capacity - 1);
  EXPECT_TRUE(f.Has(TableInvariant::kSlotOutsideWindow));
}

TEST(TableChecker, RejectsAnEmptyOrMatchingEarlierSlot) {
  Fixture f;
  const std::uint32_t i = f.PlacedRecordWithProbe(1);
  f.run.table.tags[f.run.keys[i].slot0] = f.run.keys[i].fingerprint;  // the record should have joined it
  EXPECT_TRUE(f.Has(TableInvariant::kEarlierSlotEmptyOrMatching));
}

TEST(TableChecker, RejectsAProbeFailureWithRoomInItsWindow) {
  Fixture f;
  for (std::uint32_t i = 0; i < f.run.placements.size(); ++i) {
    if (f.run.placements[i] != kProbeFailure) continue;
    f.run.table.tags[(f.run.keys[i].slot0 + 2) & (f.config.capacity - 1)] = kEmptyTag;
    break;
  }
  EXPECT_TRUE(f.Has(TableInvariant::kFailureWindowNotFull));
}

TEST(TableChecker, RejectsALostCount) {
  Fixture f;
  --f.run.table.counts[f.run.placements[f.PlacedRecordWithProbe(0)]];
  EXPECT_TRUE(f.Has(TableInvariant::kCountMismatch));
  EXPECT_TRUE(f.Has(TableInvariant::kTotalMismatch));
}

TEST(TableChecker, RejectsALostAdd) {
  Fixture f;
  f.run.table.fixed_sums[f.run.placements[f.PlacedRecordWithProbe(0)]][1] -= 1;
  EXPECT_TRUE(f.Has(TableInvariant::kSumMismatch));
  EXPECT_TRUE(f.Has(TableInvariant::kTotalMismatch));
}

TEST(TableChecker, RejectsAnEmptySlotWithContent) {
  Fixture f(1024);
  for (std::uint32_t s = 0; s < f.config.capacity; ++s) {
    if (f.run.table.tags[s] != kEmptyTag) continue;
    f.run.table.counts[s] = 1;
    break;
  }
  EXPECT_TRUE(f.Has(TableInvariant::kEmptySlotNotZero));
}

TEST(TableChecker, RejectsAnOrphanTag) {
  Fixture f(1024);
  for (std::uint32_t s = 0; s < f.config.capacity; ++s) {
    if (f.run.table.tags[s] != kEmptyTag) continue;
    f.run.table.tags[s] = 12345;
    break;
  }
  EXPECT_TRUE(f.Has(TableInvariant::kOrphanTag));
}

TEST(TableChecker, RejectsAPlacedUnkeyedRecordAndAnUnprobedKeyedOne) {
  Fixture f;
  for (std::uint32_t i = 0; i < f.run.placements.size(); ++i) {
    if (f.run.keys[i].status == shared::kKeyNoVertex) {
      f.run.placements[i] = 0;
      break;
    }
  }
  EXPECT_TRUE(f.Has(TableInvariant::kPlacementOfUnkeyedRecord));
  Fixture g;
  g.run.placements[g.PlacedRecordWithProbe(0)] = kNotPlaced;
  EXPECT_TRUE(g.Has(TableInvariant::kPlacementOfUnkeyedRecord));
}

TEST(TableChecker, ViolationsNameTheSlotAndRecords) {
  Fixture f;
  const std::uint32_t i = f.PlacedRecordWithProbe(0);
  f.run.table.tags[f.run.placements[i]] ^= 0x1u;
  const std::string text = Check(f.run, f.batch).front().ToString();
  EXPECT_NE(text.find("at slot " + std::to_string(f.run.placements[i])), std::string::npos) << text;
  EXPECT_NE(text.find("records "), std::string::npos) << text;
}

}  // namespace
}  // namespace hpsf::testing
