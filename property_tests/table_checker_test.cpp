// The table checker accepts every table the correct kernels produce, over generated batches, configs,
// schedules, warp sizes and both modes; with nothing failed or aliased the fixed64 image is the reference's,
// bit for bit. And it rejects hand-corrupted tables: for every invariant at least one plant breaks that
// invariant and nothing else, and the checker must report exactly that invariant, so no check hides behind
// another that the same corruption also trips.
#include "verifier/checker/table_checker.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <iterator>
#include <optional>
#include <ostream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/shared/eviction_priority.h"
#include "core/shared/fixed_point.h"
#include "emulated/emulated_filter.h"
#include "property_tests/constructed_cells.h"
#include "reference/reference_filter.h"
#include "verifier/generators/record_generators.h"

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

std::vector<TableViolation> Check(const EmulatedRun& run, const RecordBatch& batch,
                                  const HashTableDump* before = nullptr, const FilterConfig& config = {}) {
  TableCheckInput input{run.table, batch.records,   run.keys,     run.placements,
                        before,    config.eviction, config.frame, config.temporal};
  input.coarser_placements = run.coarser_placements;
  return CheckTable(input);
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
  config.probing = *rc::gen::element(ProbeKind::kLinear, ProbeKind::kBucket, ProbeKind::kBucketWindow);
  if (config.probing == ProbeKind::kBucket) config.probe_limit = std::bit_floor(config.probe_limit);
  RC_TAG(ToString(config.probing));
  config.fingerprint_bits = *rc::gen::inRange(8u, 33u);
  config.accumulation = *rc::gen::element(Accumulation::kFixed64, Accumulation::kFloat32);
  config.normal_in_index = *rc::gen::arbitrary<bool>();
  EmulatorOptions options;
  options.mode = *rc::gen::element(simt::Mode::kFast, simt::Mode::kFaithful);
  options.warp_size = *rc::gen::element(8u, 32u, 64u);
  options.schedule = *rc::gen::element(std::string("round-robin"), "random:" + std::to_string(seed),
                                       "pct:" + std::to_string(seed) + ":3");
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

// A correct table to corrupt: by default crowded (300 records into 64 slots: every slot taken, probe failures),
// or roomy (1024 slots: empty slots, and a few slots shared by two records); fixed64 unless a float32 sum is to
// be judged.
struct Fixture {
  explicit Fixture(std::uint32_t capacity = 64, Accumulation accumulation = Accumulation::kFixed64) {
    config.capacity = capacity;
    config.probe_limit = 4;
    config.accumulation = accumulation;
    run = EmulatedFilter(batch, config, EmulatorOptions{});
  }
  RecordBatch batch = GeneratedBatch(7, 300);
  FilterConfig config;
  EmulatedRun run;
  std::optional<HashTableDump> before;  // the table before this frame, when a plant gives one

  // The invariants the checker reports, each once: a plant must leave exactly one.
  std::set<TableInvariant> Invariants() const {
    std::set<TableInvariant> invariants;
    for (const TableViolation& v : Check(run, batch, before ? &*before : nullptr, config))
      invariants.insert(v.invariant);
    return invariants;
  }
  std::string Reported() const {
    std::string text;
    for (const TableViolation& v : Check(run, batch, before ? &*before : nullptr, config))
      text += "\n  " + v.ToString();
    return text.empty() ? " nothing" : text;
  }

  std::uint32_t Mask() const { return config.capacity - 1; }
  bool Placed(std::uint32_t i) const { return run.placements[i] < config.capacity; }
  std::uint32_t Probe(std::uint32_t i) const { return (run.placements[i] - run.keys[i].slot0) & Mask(); }
  // Whether record i went on past slot s: s lies before its slot in its window, or anywhere in a failure's.
  bool ProbedPast(std::uint32_t i, std::uint32_t s) const {
    const std::uint32_t probe = (s - run.keys[i].slot0) & Mask();
    if (run.placements[i] == kProbeFailure) return probe < config.probe_limit;
    return Placed(i) && probe < Probe(i);
  }
  std::uint32_t FindRecord(const std::function<bool(std::uint32_t)>& wanted) const {
    for (std::uint32_t i = 0; i < run.placements.size(); ++i) {
      if (wanted(i)) return i;
    }
    return kNotPlaced;
  }
  std::uint32_t FindSlot(const std::function<bool(std::uint32_t)>& wanted) const {
    for (std::uint32_t s = 0; s < config.capacity; ++s) {
      if (wanted(s)) return s;
    }
    return kNotPlaced;
  }
  std::uint32_t PlacedRecordWithProbe(std::uint32_t minimum_probe) const {
    return FindRecord([&](std::uint32_t i) { return Placed(i) && Probe(i) >= minimum_probe; });
  }
  // A placed record that shares its slot, so the slot's tag stays carried when the record leaves.
  std::uint32_t PlacedRecordWithCompany() const {
    return FindRecord([&](std::uint32_t i) { return Placed(i) && run.table.counts[run.placements[i]] >= 2; });
  }
  std::uint32_t EmptySlot() const {
    return FindSlot([&](std::uint32_t s) { return run.table.tags[s] == kEmptyTag; });
  }
  // A non-zero tag that is no record's fingerprint, so no probe can match it.
  SlotTag UnusedTag() const {
    SlotTag tag = 1;
    auto carried = [&](SlotTag t) {
      return std::any_of(run.keys.begin(), run.keys.end(), [&](const KeyResult& k) { return k.fingerprint == t; });
    };
    while (carried(tag)) ++tag;
    return tag;
  }

  // Takes record i's add out of its slot (fixed64), or makes it in slot s: the slot's count and sums stay those
  // of the records placed there, so a plant that moves a record breaks nothing per slot by accident.
  void TakeOutAdd(std::uint32_t i) {
    const std::uint32_t s = run.placements[i];
    --run.table.counts[s];
    for (int c = 0; c < 3; ++c) run.table.fixed_sums[s][c] -= FixedContribution(i, c);
  }
  void AddTo(std::uint32_t i, std::uint32_t s) {
    ++run.table.counts[s];
    for (int c = 0; c < 3; ++c) run.table.fixed_sums[s][c] += FixedContribution(i, c);
    run.placements[i] = s;
  }
  std::uint64_t FixedContribution(std::uint32_t i, int c) const {
    return shared::ToFixedPoint(batch.records[i].contribution[c], shared::PowerOfTwo(run.table.fixed_point_bits));
  }
};

TEST(TableChecker, TheFixturesAreCleanCrowdedAndRoomy) {
  Fixture crowded, roomy(1024), crowded_float(64, Accumulation::kFloat32), roomy_float(1024, Accumulation::kFloat32);
  EXPECT_TRUE(Check(crowded.run, crowded.batch).empty());
  EXPECT_TRUE(Check(roomy.run, roomy.batch).empty());
  EXPECT_TRUE(Check(crowded_float.run, crowded_float.batch).empty());
  EXPECT_TRUE(Check(roomy_float.run, roomy_float.batch).empty());
  EXPECT_GT(crowded.run.probe_failures, 0u);
  EXPECT_NE(crowded.PlacedRecordWithProbe(1), kNotPlaced);
  EXPECT_NE(std::count(roomy.run.table.tags.begin(), roomy.run.table.tags.end(), kEmptyTag), 0);
  EXPECT_NE(roomy.PlacedRecordWithCompany(), kNotPlaced);
}

// The plants, one or more per invariant. Each starts from a clean fixture and must leave exactly its invariant
// broken; where the obvious corruption would break two (a lost count also changes the total), the plant keeps
// the rest of the table consistent with it.

// A record without a vertex given a slot: the checker sets unkeyed records aside, so no slot sees it.
void PlantPlacedUnkeyedRecord(Fixture& f) {
  const std::uint32_t i = f.FindRecord([&](std::uint32_t j) { return f.run.keys[j].status == shared::kKeyNoVertex; });
  ASSERT_NE(i, kNotPlaced);
  f.run.placements[i] = f.run.placements[f.PlacedRecordWithProbe(0)];
}

// A keyed record never probed: its add is taken out too, and it leaves company behind to carry the tag.
void PlantKeyedRecordNeverProbed(Fixture& f) {
  const std::uint32_t i = f.PlacedRecordWithCompany();
  ASSERT_NE(i, kNotPlaced);
  f.TakeOutAdd(i);
  f.run.placements[i] = kNotPlaced;
}

// As if the backend probed one slot more than probe_limit: the record sits at probe probe_limit behind a window
// full of other tags. Moving slot0 back is that state; moving the record instead would break its slot.
void PlantSlotPastTheWindow(Fixture& f) {
  const std::uint32_t i = f.FindRecord([&](std::uint32_t j) {
    if (!f.Placed(j)) return false;
    for (std::uint32_t back = 1; back <= f.config.probe_limit; ++back) {
      const SlotTag tag = f.run.table.tags[(f.run.placements[j] - back) & f.Mask()];
      if (tag == kEmptyTag || tag == f.run.keys[j].fingerprint) return false;
    }
    return true;
  });
  ASSERT_NE(i, kNotPlaced);
  f.run.keys[i].slot0 = (f.run.placements[i] - f.config.probe_limit) & f.Mask();
}

// A placement beyond the table, its add taken out of the slot it was in.
void PlantSlotBeyondTheTable(Fixture& f) {
  const std::uint32_t i = f.PlacedRecordWithCompany();
  ASSERT_NE(i, kNotPlaced);
  f.TakeOutAdd(i);
  f.run.placements[i] = f.config.capacity;
}

// A slot's tag replaced by one no record carries: no probe could have matched it, and the slot keeps its
// records, so only they see the wrong tag.
void PlantChangedTag(Fixture& f) {
  const std::uint32_t i = f.PlacedRecordWithProbe(0);
  ASSERT_NE(i, kNotPlaced);
  f.run.table.tags[f.run.placements[i]] = f.UnusedTag();
}

// A record alone in its first slot moved, with its tag, count and sums, to the empty slot after it: it skipped
// an empty slot. Nobody else probed past that slot, so the empty slot troubles no other record.
void PlantSkippedEmptySlot(Fixture& f) {
  const std::uint32_t i = f.FindRecord([&](std::uint32_t j) {
    if (!f.Placed(j) || f.Probe(j) != 0) return false;
    const std::uint32_t s = f.run.placements[j];
    if (f.run.table.counts[s] != 1 || f.run.table.tags[(s + 1) & f.Mask()] != kEmptyTag) return false;
    for (std::uint32_t k = 0; k < f.run.placements.size(); ++k) {
      if (k != j && f.ProbedPast(k, s)) return false;
    }
    return true;
  });
  ASSERT_NE(i, kNotPlaced);
  ASSERT_GE(f.config.probe_limit, 2u);
  const std::uint32_t s = f.run.placements[i], next = (s + 1) & f.Mask();
  f.TakeOutAdd(i);
  f.run.table.tags[next] = f.run.table.tags[s];
  f.run.table.tags[s] = kEmptyTag;
  f.AddTo(i, next);
}

// One of a slot's records moved to the empty slot after it, under the same tag: it passed a slot it should
// have joined. The slot it left keeps company and the right count and sums.
void PlantPassedItsOwnTag(Fixture& f) {
  const std::uint32_t i = f.FindRecord([&](std::uint32_t j) {
    if (!f.Placed(j) || f.Probe(j) != 0) return false;
    const std::uint32_t s = f.run.placements[j];
    return f.run.table.counts[s] >= 2 && f.run.table.tags[(s + 1) & f.Mask()] == kEmptyTag;
  });
  ASSERT_NE(i, kNotPlaced);
  ASSERT_GE(f.config.probe_limit, 2u);
  const std::uint32_t s = f.run.placements[i], next = (s + 1) & f.Mask();
  f.TakeOutAdd(i);
  f.run.table.tags[next] = f.run.table.tags[s];
  f.AddTo(i, next);
}

// A placed record turned into a probe failure, its add taken out: its window still holds its own tag, carried
// by the company it leaves.
void PlantFailureBesideItsOwnTag(Fixture& f) {
  const std::uint32_t i = f.PlacedRecordWithCompany();
  ASSERT_NE(i, kNotPlaced);
  f.TakeOutAdd(i);
  f.run.placements[i] = kProbeFailure;
}

// One count moved from one slot to another: both slots are wrong, the table's total count is not.
void PlantCountMovedBetweenSlots(Fixture& f) {
  const std::uint32_t from = f.FindSlot([&](std::uint32_t s) { return f.run.table.counts[s] > 0; });
  ASSERT_NE(from, kNotPlaced);
  const std::uint32_t to = f.FindSlot([&](std::uint32_t s) { return s != from && f.run.table.tags[s] != kEmptyTag; });
  ASSERT_NE(to, kNotPlaced);
  --f.run.table.counts[from];
  ++f.run.table.counts[to];
}

// One fixed64 unit moved between two slots' sums: both sums are wrong, the channel's total is not.
void PlantFixedSumMovedBetweenSlots(Fixture& f) {
  const std::uint32_t from = f.FindSlot([&](std::uint32_t s) { return f.run.table.fixed_sums[s][1] > 0; });
  ASSERT_NE(from, kNotPlaced);
  const std::uint32_t to = f.FindSlot([&](std::uint32_t s) { return s != from && f.run.table.tags[s] != kEmptyTag; });
  ASSERT_NE(to, kNotPlaced);
  f.run.table.fixed_sums[from][1] -= 1;
  f.run.table.fixed_sums[to][1] += 1;
}

// With second moments: one unit of a square sum moved to another live slot (the square total kept), in a table run
// again with them kept.
void PlantSquareSumMovedBetweenSlots(Fixture& f) {
  f.config.second_moments = true;
  f.run = EmulatedFilter(f.batch, f.config, EmulatorOptions{});
  ASSERT_TRUE(f.Invariants().empty()) << f.Reported();
  const std::uint32_t from = f.FindSlot([&](std::uint32_t s) { return f.run.table.fixed_squares[s] > 0; });
  ASSERT_NE(from, kNotPlaced);
  const std::uint32_t to = f.FindSlot([&](std::uint32_t s) { return s != from && f.run.table.tags[s] != kEmptyTag; });
  ASSERT_NE(to, kNotPlaced);
  f.run.table.fixed_squares[from] -= 1;
  f.run.table.fixed_squares[to] += 1;
}

// float32: a slot of n >= 2 records whose sum lies a few ulps past gamma(n-1) * sum|c| from the exact sum.
// float32 has no total of sums to keep.
void PlantFloatSumOutsideTheBound(Fixture& f) {
  const int c = 0;
  const std::uint32_t s = f.FindSlot([&](std::uint32_t t) {
    return f.run.table.tags[t] != kEmptyTag && f.run.table.counts[t] >= 2 && f.run.table.float_sums[t][c] > 0.0f;
  });
  ASSERT_NE(s, kNotPlaced);
  double exact = 0.0, magnitude = 0.0;
  for (std::uint32_t i = 0; i < f.run.placements.size(); ++i) {
    if (f.run.placements[i] != s) continue;
    exact += double(f.batch.records[i].contribution[c]);
    magnitude += std::abs(double(f.batch.records[i].contribution[c]));
  }
  const double k = double(f.run.table.counts[s] - 1), u = 0x1p-23;
  const double bound = k * u / (1.0 - k * u) * magnitude;
  // Rounding to float moves it by at most u * |sum| <= bound, so 4 bounds land at least 3 past the sum.
  f.run.table.float_sums[s][c] = float(exact + 4.0 * bound);
}

// float32: a slot of one record, its sum one ulp off: one add has no rounding, so the bound is 0.
void PlantFloatSumOfOneRecordOffByAnUlp(Fixture& f) {
  const std::uint32_t s = f.FindSlot([&](std::uint32_t t) {
    return f.run.table.tags[t] != kEmptyTag && f.run.table.counts[t] == 1 && f.run.table.float_sums[t][2] > 0.0f;
  });
  ASSERT_NE(s, kNotPlaced);
  f.run.table.float_sums[s][2] = std::nextafter(f.run.table.float_sums[s][2], 0.0f);
}

// An empty slot with a count, or with a sum; empty slots do not enter the totals.
void PlantEmptySlotWithACount(Fixture& f) {
  const std::uint32_t s = f.EmptySlot();
  ASSERT_NE(s, kNotPlaced);
  f.run.table.counts[s] = 1;
}
void PlantEmptySlotWithASum(Fixture& f) {
  const std::uint32_t s = f.EmptySlot();
  ASSERT_NE(s, kNotPlaced);
  f.run.table.fixed_sums[s][2] = 1;
}

// An empty slot given a tag no record carries: no record probed past an empty slot, so none sees it.
void PlantOrphanTag(Fixture& f) {
  const std::uint32_t s = f.EmptySlot();
  ASSERT_NE(s, kNotPlaced);
  f.run.table.tags[s] = f.UnusedTag();
}

// Over frames: the table before this frame had claimed a slot that is empty after it (an eviction without a policy
// that allows it, or a table cleared between frames). The slot held no count or sum, so only its tag tells.
void PlantTagLostAcrossFrames(Fixture& f) {
  const std::uint32_t s = f.EmptySlot();
  ASSERT_NE(s, kNotPlaced);
  HashTableDump before = f.run.table;
  std::fill(before.tags.begin(), before.tags.end(), kEmptyTag);
  std::fill(before.counts.begin(), before.counts.end(), 0);
  std::fill(before.fixed_sums.begin(), before.fixed_sums.end(), std::array<std::uint64_t, 3>{});
  before.tags[s] = f.UnusedTag();
  f.before = before;
}

// The per-slot checks imply the total wherever records sit on tagged slots. A fingerprint of 0 (core never
// makes one: 0 marks an empty slot) lets a record sit, unseen by them, on a slot whose tag and count stayed 0:
// only the total sees the missing add. The record's add is taken out of its old slot, which keeps company.
void PlantRecordOnAnUntaggedSlot(Fixture& f) {
  const std::uint32_t i = f.PlacedRecordWithCompany(), s = f.EmptySlot();
  ASSERT_NE(i, kNotPlaced);
  ASSERT_NE(s, kNotPlaced);
  f.TakeOutAdd(i);
  f.run.keys[i].fingerprint = kEmptyTag;
  f.run.keys[i].slot0 = s;
  f.run.placements[i] = s;
}

// Over frames with strict eviction: the fixture's table becomes frame 0's, and frame 1 keeps the vertex of every
// third record only, so the cells left without one are evicted. Some become tombstones kept before a live slot,
// others are reclaimed.
void EvictingSecondFrame(Fixture& f) {
  f.config.frames = 2;
  f.config.eviction = ParseEviction("strict");
  const EmulatedRun first = EmulatedFilter(f.batch, f.config, EmulatorOptions{});
  for (std::size_t i = 0; i < f.batch.records.size(); ++i) {
    if (i % 3 != 0) f.batch.records[i].path.z &= ~shared::kRecordHasVertex;
  }
  f.config.frame = 1;
  f.run = EmulatedFilter(f.batch, f.config, EmulatorOptions{}, AccumulateKernel, &first.table);
  f.before = first.table;
  ASSERT_TRUE(f.Invariants().empty()) << f.Reported();
  ASSERT_GT(f.run.evicted, 0u);
}
bool Tombstone(const HashTableDump& table, std::uint32_t s) {
  return table.tags[s] != kEmptyTag && table.counts[s] == 0;
}

// Over frames with an EMA: frame 1 repeats frame 0's records without jitter (so in the same cells), every cell's
// history weighs 1/2 by integration, and ema:0.25 blends them all.
void BlendingSecondFrame(Fixture& f) {
  f.config.frames = 2;
  f.config.jitter_scale = 0.0f;
  f.config.temporal = ParseTemporal("ema:0.25");
  const EmulatedRun first = EmulatedFilter(f.batch, f.config, EmulatorOptions{});
  f.config.frame = 1;
  f.run = EmulatedFilter(f.batch, f.config, EmulatorOptions{}, AccumulateKernel, &first.table);
  f.before = first.table;
  ASSERT_TRUE(f.Invariants().empty()) << f.Reported();
}

// A blended slot one unit of 2^-F off the blend in one channel.
// packed-decimal: a slot's frame counter left where it was before the settle (a settle that skipped the slot).
void PlantPackedFrameCounterNotAdvanced(Fixture& f) {
  const std::uint32_t slot = f.run.placements[f.PlacedRecordWithProbe(0)];
  ASSERT_EQ(f.run.table.frame_counters[slot], 1u);
  f.run.table.frame_counters[slot] = 0;
}

void PlantBlendOffByOne(Fixture& f) {
  BlendingSecondFrame(f);
  const std::uint32_t s = f.FindSlot([&](std::uint32_t s) {
    const std::uint64_t before = f.before->counts[s], after = f.run.table.counts[s];
    return before > 0 && after != before && after < 2 * before;
  });
  ASSERT_NE(s, kNotPlaced) << "no blended slot";
  f.run.table.fixed_sums[s][1] += 1;
}

// An evicted slot whose count and sums came back: the policy evicts it (strict: untouched this frame).
void PlantEvictedEstimateBack(Fixture& f) {
  EvictingSecondFrame(f);
  const std::uint32_t s = f.FindSlot([&](std::uint32_t s) { return Tombstone(f.run.table, s); });
  ASSERT_NE(s, kNotPlaced);
  f.run.table.counts[s] = f.before->counts[s];
  f.run.table.fixed_sums[s] = f.before->fixed_sums[s];
}

// A slot this frame touched that still names an earlier frame as its last.
void PlantStaleLastSeen(Fixture& f) {
  EvictingSecondFrame(f);
  const std::uint32_t s = f.FindSlot([&](std::uint32_t s) { return f.run.table.counts[s] > f.before->counts[s]; });
  ASSERT_NE(s, kNotPlaced);
  f.run.table.last_seen[s] = 0;
}

// D7: a tombstone kept before a live slot emptied. One no record of this frame probed past, so only the tombstone
// check sees the hole (a record that did would also report its empty earlier slot).
void PlantHoleBeforeALiveSlot(Fixture& f) {
  EvictingSecondFrame(f);
  const std::uint32_t s = f.FindSlot([&](std::uint32_t s) {
    if (!Tombstone(f.run.table, s)) return false;
    for (std::uint32_t i = 0; i < f.batch.records.size(); ++i) {
      if (f.ProbedPast(i, s)) return false;
    }
    return true;
  });
  ASSERT_NE(s, kNotPlaced);
  f.run.table.tags[s] = kEmptyTag;
}

// A tombstone the reclaim emptied, given its tag back: nothing needs it, and kept ones fill the table for good.
void PlantUnneededTombstone(Fixture& f) {
  EvictingSecondFrame(f);
  const std::uint32_t s =
      f.FindSlot([&](std::uint32_t s) { return f.before->tags[s] != kEmptyTag && f.run.table.tags[s] == kEmptyTag; });
  ASSERT_NE(s, kNotPlaced);
  f.run.table.tags[s] = f.before->tags[s];
}

// Priority: cell B lived at slot0 + 1 past A's tombstone at slot0; frame 1's record of B claimed the tombstone
// instead of finding B, splitting the cell (an insertion without its search). Constructed cells in 4 slots, the
// table otherwise consistent with the move.
void PlantCellSplitPastATombstone(Fixture& f) {
  f.config = ConstructedConfig(4, 4, 24);
  f.config.frames = 2;
  f.config.eviction = ParseEviction("priority");
  const glm::ivec3 a = FindCell(f.config, [](const KeyResult& k) { return k.slot0 == 0u; });
  const std::uint32_t fingerprint_a = KeyOfCell(f.config, a).fingerprint;
  const glm::ivec3 b = FindCell(
      f.config, [&](const KeyResult& k) { return k.slot0 == 0u && k.fingerprint != fingerprint_a; }, a.x + 1);
  HashTableDump before = EmulatedFilter(BatchOfCells({a, b}), f.config, EmulatorOptions{}).table;
  ASSERT_EQ(before.tags[1], KeyOfCell(f.config, b).fingerprint);
  before.tags[0] = shared::kTombstoneTag;  // A, evicted under pressure
  before.counts[0] = 0;
  before.fixed_sums[0] = {};
  f.batch = BatchOfCells({b});
  f.batch.frame = 1;
  f.config.frame = 1;
  f.run = EmulatedFilter(f.batch, f.config, EmulatorOptions{}, AccumulateKernel, &before);
  f.before = before;
  ASSERT_EQ(f.run.placements[0], 1u) << "B's record did not find B past the tombstone";
  ASSERT_TRUE(f.Invariants().empty()) << f.Reported();
  HashTableDump& t = f.run.table;
  t.tags[0] = t.tags[1];
  t.counts[0] = 1;
  t.fixed_sums[0] = {f.FixedContribution(0, 0), f.FixedContribution(0, 1), f.FixedContribution(0, 2)};
  t.last_seen[0] = 1;
  t.counts[1] = before.counts[1];
  t.fixed_sums[1] = before.fixed_sums[1];
  t.last_seen[1] = before.last_seen[1];
  f.run.placements[0] = 0;
}

// Compaction over two frames with eviction: the list after frame 1 loses the entry of a slot still occupied (a prune
// that dropped it, or a gather that never listed it).
void PlantSlotMissingFromTheList(Fixture& f) {
  f.config.compaction = Compaction::kOccupiedList;
  EvictingSecondFrame(f);
  ASSERT_TRUE(f.run.table.compacted);
  ASSERT_GT(f.run.table.occupied.size(), 1u);
  f.run.table.occupied.pop_back();
}

// Two levels (core/shared/levels.h): a slot one level up that lost one of its children's adds (its count one short,
// as a lost atomic leaves it).
void PlantCoarserCellLostAChildsAdd(Fixture& f) {
  f.config.levels = 2;
  f.run = EmulatedFilter(f.batch, f.config, EmulatorOptions{});
  ASSERT_TRUE(f.Invariants().empty()) << f.Reported();
  for (const std::uint32_t slot : f.run.coarser_placements) {
    if (slot < f.config.capacity && f.run.table.counts[slot] > 1) {
      --f.run.table.counts[slot];
      return;
    }
  }
  FAIL() << "no coarser slot of two records";
}

struct IsolatedCase {
  const char* name;
  TableInvariant invariant;
  std::uint32_t capacity;  // 64: crowded, 1024: roomy
  Accumulation accumulation;
  void (*plant)(Fixture&);
  // What the invariant cannot be broken without: the level nesting is implied by each touch's count and sums
  // (verifier/checker/table_checker.h), so a coarser slot that lost a child's add breaks its count too.
  std::set<TableInvariant> implied = {};
};
void PrintTo(const IsolatedCase& c, std::ostream* os) { *os << c.name; }

constexpr std::uint32_t kCrowded = 64, kRoomy = 1024;
constexpr Accumulation kFixed64 = Accumulation::kFixed64, kFloat32 = Accumulation::kFloat32,
                       kPacked = Accumulation::kPackedDecimal;

const IsolatedCase kIsolatedCases[] = {
    {"PlacedUnkeyedRecord", TableInvariant::kPlacementOfUnkeyedRecord, kCrowded, kFixed64, PlantPlacedUnkeyedRecord},
    {"KeyedRecordNeverProbed", TableInvariant::kPlacementOfUnkeyedRecord, kRoomy, kFixed64,
     PlantKeyedRecordNeverProbed},
    {"SlotPastTheWindow", TableInvariant::kSlotOutsideWindow, kCrowded, kFixed64, PlantSlotPastTheWindow},
    {"SlotBeyondTheTable", TableInvariant::kSlotOutsideWindow, kRoomy, kFixed64, PlantSlotBeyondTheTable},
    {"ChangedTag", TableInvariant::kTagIsNotTheFingerprint, kCrowded, kFixed64, PlantChangedTag},
    {"SkippedEmptySlot", TableInvariant::kEarlierSlotEmptyOrMatching, kRoomy, kFixed64, PlantSkippedEmptySlot},
    {"PassedItsOwnTag", TableInvariant::kEarlierSlotEmptyOrMatching, kRoomy, kFixed64, PlantPassedItsOwnTag},
    {"FailureBesideItsOwnTag", TableInvariant::kFailureWindowNotFull, kRoomy, kFixed64, PlantFailureBesideItsOwnTag},
    {"CountMovedBetweenSlots", TableInvariant::kCountMismatch, kCrowded, kFixed64, PlantCountMovedBetweenSlots},
    {"FixedSumMovedBetweenSlots", TableInvariant::kSumMismatch, kCrowded, kFixed64, PlantFixedSumMovedBetweenSlots},
    {"FloatSumOutsideTheBound", TableInvariant::kSumMismatch, kRoomy, kFloat32, PlantFloatSumOutsideTheBound},
    {"SquareSumMovedBetweenSlots", TableInvariant::kSquareSumMismatch, kCrowded, kFixed64,
     PlantSquareSumMovedBetweenSlots},
    {"FloatSumOfOneRecordOffByAnUlp", TableInvariant::kSumMismatch, kCrowded, kFloat32,
     PlantFloatSumOfOneRecordOffByAnUlp},
    {"EmptySlotWithACount", TableInvariant::kEmptySlotNotZero, kRoomy, kFixed64, PlantEmptySlotWithACount},
    {"EmptySlotWithASum", TableInvariant::kEmptySlotNotZero, kRoomy, kFixed64, PlantEmptySlotWithASum},
    {"OrphanTag", TableInvariant::kOrphanTag, kRoomy, kFixed64, PlantOrphanTag},
    {"RecordOnAnUntaggedSlot", TableInvariant::kTotalMismatch, kRoomy, kFixed64, PlantRecordOnAnUntaggedSlot},
    {"TagLostAcrossFrames", TableInvariant::kTagChangedAcrossFrames, kRoomy, kFixed64, PlantTagLostAcrossFrames},
    {"EvictedEstimateBack", TableInvariant::kEvictionPolicy, kRoomy, kFixed64, PlantEvictedEstimateBack},
    {"StaleLastSeen", TableInvariant::kLastSeenWrong, kRoomy, kFixed64, PlantStaleLastSeen},
    {"HoleBeforeALiveSlot", TableInvariant::kHoleBeforeLiveSlot, kRoomy, kFixed64, PlantHoleBeforeALiveSlot},
    {"UnneededTombstone", TableInvariant::kTombstoneKept, kRoomy, kFixed64, PlantUnneededTombstone},
    {"BlendOffByOne", TableInvariant::kTemporalBlend, kRoomy, kFixed64, PlantBlendOffByOne},
    {"CellSplitPastATombstone", TableInvariant::kCellSplit, kRoomy, kFixed64, PlantCellSplitPastATombstone},
    {"SlotMissingFromTheList", TableInvariant::kOccupiedList, kRoomy, kFixed64, PlantSlotMissingFromTheList},
    {"PackedFrameCounterNotAdvanced", TableInvariant::kPackedSettle, kRoomy, kPacked,
     PlantPackedFrameCounterNotAdvanced},
    {"CoarserCellLostAChildsAdd",
     TableInvariant::kLevelNesting,
     kRoomy,
     kFixed64,
     PlantCoarserCellLostAChildsAdd,
     {TableInvariant::kCountMismatch, TableInvariant::kTotalMismatch}},
};

class IsolatedViolation : public ::testing::TestWithParam<IsolatedCase> {};

TEST_P(IsolatedViolation, IsTheOnlyInvariantReported) {
  const IsolatedCase& c = GetParam();
  Fixture f(c.capacity, c.accumulation);
  ASSERT_TRUE(f.Invariants().empty()) << f.Reported();
  c.plant(f);
  if (HasFatalFailure()) return;
  std::set<TableInvariant> wanted = c.implied;
  wanted.insert(c.invariant);
  EXPECT_EQ(f.Invariants(), wanted) << "wanted only \"" << ToString(c.invariant)
                                    << "\" (and what it implies), reported:" << f.Reported();
}

INSTANTIATE_TEST_SUITE_P(TableChecker, IsolatedViolation, ::testing::ValuesIn(kIsolatedCases),
                         [](const auto& info) { return std::string(info.param.name); });

// Every enumerator, found through ToString (whose switch the compiler checks for completeness), has a plant
// that breaks it alone: a new invariant without one fails here.
TEST(TableChecker, EveryInvariantHasAnIsolatedCase) {
  int enumerators = 0;
  for (int v = 0; std::strcmp(ToString(TableInvariant(v)), "?") != 0; ++v, ++enumerators) {
    const bool covered = std::any_of(std::begin(kIsolatedCases), std::end(kIsolatedCases),
                                     [&](const IsolatedCase& c) { return c.invariant == TableInvariant(v); });
    EXPECT_TRUE(covered) << "no plant breaks \"" << ToString(TableInvariant(v)) << "\" alone";
  }
  EXPECT_GT(enumerators, int(TableInvariant::kTotalMismatch));
}

TEST(TableChecker, ViolationsNameTheSlotAndRecords) {
  Fixture f;
  const std::uint32_t i = f.PlacedRecordWithProbe(0);
  f.run.table.tags[f.run.placements[i]] ^= 0x1u;
  const std::vector<TableViolation> violations = Check(f.run, f.batch);
  ASSERT_FALSE(violations.empty());  // a failure, not a crash, if the tag check goes
  const std::string text = violations.front().ToString();
  EXPECT_NE(text.find("at slot " + std::to_string(f.run.placements[i])), std::string::npos) << text;
  EXPECT_NE(text.find("records "), std::string::npos) << text;
}

}  // namespace
}  // namespace hpsf::testing
