// Compaction into a list of occupied slots (core/compaction.h) on every hashed backend (emulated fast and faithful,
// Vulkan mapped and staged): a sequence run with the list leaves, frame by frame, the same table bit for bit as one
// run without it, under every eviction policy, a blending temporal mode and level seeds; the list holds each occupied
// slot once and nothing else, and the checker passes it; the checker names a list that misses, repeats or adds a
// slot; and Bevy #21904's prune, whose count is 1 when it kept nothing, is caught in the emulator and as a shader.

#include "core/compaction.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend.h"
#include "core/error.h"
#include "core/shared/record_layout.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "emulated/emulated_filter.h"
#include "property_tests/hashed_backends.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "tracer/scene_file.h"
#include "verifier/checker/table_checker.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf::testing {
namespace {

std::vector<std::uint32_t> OccupiedSlots(const HashTableDump& table) {
  std::vector<std::uint32_t> slots;
  for (std::uint32_t s = 0; s < table.capacity; ++s) {
    if (table.tags[s] != kEmptyTag) slots.push_back(s);
  }
  return slots;
}

// Per record: its slot's tag, count, sums and last-seen frame, or its placement where it has no slot.
std::vector<std::vector<std::uint64_t>> CellsOfRecords(const HashedRun& run) {
  std::vector<std::vector<std::uint64_t>> cells;
  const HashTableDump& t = run.table;
  for (const std::uint32_t slot : run.placements) {
    if (slot >= t.capacity) {
      cells.push_back({slot});
      continue;
    }
    cells.push_back({t.tags[slot], t.counts[slot], t.fixed_sums[slot][0], t.fixed_sums[slot][1], t.fixed_sums[slot][2],
                     t.last_seen.empty() ? 0 : t.last_seen[slot]});
  }
  return cells;
}

std::vector<TableViolation> Check(const HashedRun& run, const RecordBatch& batch, const FilterConfig& config,
                                  const HashTableDump* before) {
  return CheckTable({run.table, batch.records, run.keys, run.placements, before, config.eviction, config.frame,
                     config.temporal, config.level_seed, config.normal_in_index});
}

TEST(Compaction, ParsesItsModesAndNamesABadOne) {
  EXPECT_EQ(ParseCompaction("none"), Compaction::kNone);
  EXPECT_EQ(ParseCompaction("occupied-list"), Compaction::kOccupiedList);
  EXPECT_EQ(ToString(Compaction::kOccupiedList), "occupied-list");
  for (const char* bad : {"", "list", "occupied", "Occupied-list", "occupied-list "}) {
    try {
      ParseCompaction(bad);
      ADD_FAILURE() << bad << " parsed";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--compaction: ", 0), 0u) << e.what();
    }
  }
}

// The animated Cornell box evicts, keeps tombstones and reclaims every frame: the list both grows and shrinks.
TEST(Compaction, TheListedTableIsBitForBitTheUnlistedOneOnEveryHashedBackend) {
  constexpr std::uint32_t kFrames = 6;
  const std::vector<RecordBatch> frames =
      TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), 24, 2, kFrames);
  struct Passes {
    const char* eviction;
    const char* temporal;
    const char* level_change;
    std::uint32_t capacity;
  };
  for (const Passes& passes :
       {Passes{"strict", "integrate", "none", 1u << 12}, Passes{"stale:2", "ema:0.2", "seed", 1u << 12},
        Passes{"priority", "adaptive", "none", 256u}, Passes{"none", "ema:0.5", "none", 1u << 12}}) {
    std::vector<HashedBackend> listed = HashedBackends(), unlisted = HashedBackends();
    for (std::size_t b = 0; b < listed.size(); ++b) {
      const std::string name = listed[b].name + ", " + passes.eviction + ", " + passes.temporal;
      FilterConfig config;
      config.capacity = passes.capacity;
      config.frames = kFrames;
      config.fingerprint_bits = 31;  // priority's tombstone tag
      config.eviction = ParseEviction(passes.eviction);
      config.temporal = ParseTemporal(passes.temporal);
      config.level_seed = ParseLevelSeed(passes.level_change);
      FilterConfig with_list = config;
      with_list.compaction = Compaction::kOccupiedList;
      std::optional<HashTableDump> before;
      bool grew = false, shrank = false, failed = false;
      std::uint64_t evicted = 0;
      for (std::uint32_t k = 0; k < kFrames; ++k) {
        config.frame = with_list.frame = k;
        const std::string what = name + ", frame " + std::to_string(k);
        const Image& image = listed[b].backend->FilterFrame(frames[k], with_list);
        const Image& expected = unlisted[b].backend->FilterFrame(frames[k], config);
        const HashTableDump& table = RunOf(*listed[b].backend).table;
        const HashTableDump& plain = RunOf(*unlisted[b].backend).table;
        // What level 4 promises: each record's cell and the image where nothing failed, in this frame or before
        // (which records of a crowded table fail depends on fast mode's threads and the device's order); the whole
        // table where the schedule is the seed's alone.
        const bool faithful = listed[b].name == "emulated faithful";
        failed |= RunOf(*listed[b].backend).probe_failures + RunOf(*unlisted[b].backend).probe_failures > 0;
        if (faithful || !failed) {
          EXPECT_TRUE(image.pixels == expected.pixels) << what;
          EXPECT_EQ(CellsOfRecords(RunOf(*listed[b].backend)), CellsOfRecords(RunOf(*unlisted[b].backend))) << what;
        }
        if (faithful) {
          EXPECT_TRUE(table.tags == plain.tags && table.counts == plain.counts &&
                      table.fixed_sums == plain.fixed_sums && table.last_seen == plain.last_seen)
              << what << ": the listed table differs from the unlisted one";
        }
        ASSERT_TRUE(table.compacted) << what;
        EXPECT_FALSE(plain.compacted) << what;
        std::vector<std::uint32_t> occupied = table.occupied;
        std::sort(occupied.begin(), occupied.end());
        EXPECT_EQ(occupied, OccupiedSlots(table)) << what;
        const std::vector<TableViolation> violations =
            Check(RunOf(*listed[b].backend), frames[k], with_list, before ? &*before : nullptr);
        EXPECT_TRUE(violations.empty()) << what << ": " << violations.front().ToString();
        evicted += RunOf(*listed[b].backend).evicted;
        if (before) {
          grew |= table.occupied.size() > before->occupied.size();
          shrank |= table.occupied.size() < before->occupied.size();
        }
        before = table;
      }
      // The list is fed: entries gathered frame after frame, and pruned where eviction by age reclaims slots;
      // priority's table of 256 slots is full from the first frame and evicts under pressure.
      if (config.eviction.by_priority()) {
        EXPECT_GT(evicted, 0u) << name;
      } else {
        EXPECT_TRUE(grew) << name;
        EXPECT_EQ(shrank, config.eviction.enabled()) << name;
      }
    }
  }
}

// A compacted table handed from the emulator to the device (VulkanFilter::LoadTable): its list and flags go with it,
// and the device's next frames leave the emulator's bits, the list still the table's.
TEST(Compaction, AListedTableLoadedOntoTheDeviceCarriesOn) {
  constexpr std::uint32_t kFrames = 4;
  const std::vector<RecordBatch> frames =
      TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), 24, 2, kFrames);
  FilterConfig config;
  config.capacity = 1u << 12;
  config.frames = kFrames;
  config.eviction = ParseEviction("strict");
  config.temporal = ParseTemporal("ema:0.5");
  config.compaction = Compaction::kOccupiedList;
  EmulatorOptions faithful;
  faithful.mode = simt::Mode::kFaithful;
  faithful.warp_size = 8;
  faithful.schedule = "round-robin";
  std::vector<EmulatedRun> emulated;
  for (std::uint32_t k = 0; k < kFrames; ++k) {
    config.frame = k;
    emulated.push_back(
        EmulatedFilter(frames[k], config, faithful, AccumulateKernel, k > 0 ? &emulated.back().table : nullptr));
  }
  for (const StagingPolicy staging : kStagingPolicies) {
    VulkanFilter vulkan(TestDevice(staging));
    vulkan.LoadTable(emulated[1].table);
    HashTableDump before = emulated[1].table;
    for (std::uint32_t k = 2; k < kFrames; ++k) {
      config.frame = k;
      const std::optional<VulkanRun> run = vulkan.Run(frames[k], config, true);
      const std::string what = std::string("staging ") + ToString(staging) + ", frame " + std::to_string(k);
      EXPECT_EQ(CellsOfRecords(*run), CellsOfRecords(emulated[k])) << what;
      EXPECT_TRUE(run->image.pixels == emulated[k].image.pixels) << what;
      const std::vector<TableViolation> violations = Check(*run, frames[k], config, &before);
      EXPECT_TRUE(violations.empty()) << what << ": " << violations.front().ToString();
      before = run->table;
    }
  }
  HashTableDump unlisted = emulated[1].table;
  unlisted.compacted = false;
  unlisted.occupied.clear();
  VulkanFilter vulkan(TestDevice(kStagingPolicies[0]));
  vulkan.LoadTable(unlisted);
  config.frame = 2;
  try {
    vulkan.Run(frames[2], config, true);
    ADD_FAILURE() << "a table without a list carried on with compaction";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--compaction: the device table has no occupied list"), std::string::npos)
        << e.what();
  }
}

TEST(Compaction, TheCheckerNamesAMissingARepeatedAndAnEmptyListedSlot) {
  HashTableDump table;
  table.capacity = 8;
  table.probe_limit = 8;
  table.tags.assign(8, kEmptyTag);
  table.counts.assign(8, 0);
  table.fixed_sums.assign(8, {});
  table.compacted = true;
  table.tags[1] = table.tags[3] = table.tags[5] = 7;  // tombstones: a tag, no count
  const auto violations = [&](std::vector<std::uint32_t> occupied) {
    table.occupied = std::move(occupied);
    std::vector<std::string> found;
    for (const TableViolation& v : CheckTable({table, {}, {}, {}})) {
      if (v.invariant == TableInvariant::kOccupiedList) found.push_back(v.ToString());  // not the orphan tags'
    }
    return found;
  };
  EXPECT_TRUE(violations({5, 1, 3}).empty());
  const std::vector<std::string> found = violations({1, 3, 3, 6});
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[0], "occupied list differs from the occupied slots at slot 3: entry 2 lists it again");
  EXPECT_EQ(found[1], "occupied list differs from the occupied slots at slot 6: entry 3 lists it, but it is empty");
  EXPECT_EQ(found[2],
            "occupied list differs from the occupied slots at slot 5: occupied (tag 7), but not in the list of 4");
  EXPECT_EQ(violations({1, 3, 5, 9}).size(), 1u);  // past the table's end
}

// Bevy #21904: a frame that evicts and reclaims every slot leaves an empty list, which the broken prune counts as
// one entry, naming a slot that holds nothing.
TEST(Compaction, Bevy21904ACountOfOneWithNothingListedIsCaught) {
  const RecordBatch seen = TracedBatch("cornell", 16, 1);
  RecordBatch sky = seen;  // the same pixels with no vertex: the table is touched nowhere
  for (Record& r : sky.records) r.path.z &= ~shared::kRecordHasVertex;
  const std::vector<RecordBatch> frames = {seen, sky, seen};
  FilterConfig config;
  config.capacity = 1u << 12;
  config.frames = 3;
  config.eviction = ParseEviction("strict");
  config.compaction = Compaction::kOccupiedList;
  auto violations_of = [&](Backend& backend) {
    std::vector<std::vector<TableViolation>> per_frame;
    std::optional<HashTableDump> before;
    for (std::uint32_t k = 0; k < frames.size(); ++k) {
      config.frame = k;
      backend.FilterFrame(frames[k], config);
      per_frame.push_back(Check(RunOf(backend), frames[k], config, before ? &*before : nullptr));
      if (k == 1) {
        EXPECT_TRUE(OccupiedSlots(RunOf(backend).table).empty()) << "the sky frame empties the table";
      }
      before = RunOf(backend).table;
    }
    return per_frame;
  };
  for (HashedBackend& right : HashedBackends()) {
    for (const std::vector<TableViolation>& frame : violations_of(*right.backend)) {
      EXPECT_TRUE(frame.empty()) << right.name << ": " << frame.front().ToString();
    }
  }
  std::vector<HashedBackend> broken;
  broken.push_back({"emulated", std::make_unique<EmulatedBackend>(EmulatorOptions{}, AccumulateKernel,
                                                                  EvictionKernels(ReclaimKernel, SelectVictimsKernel,
                                                                                  FinishPruneCountOneWhenEmpty))});
  for (const StagingPolicy staging : kStagingPolicies) {
    broken.push_back({std::string("vulkan, staging ") + ToString(staging),
                      std::make_unique<VulkanBackend>(TestDevice(staging), "", "", "", "",
                                                      HPSF_SHADER_VARIANT_DIR "/compaction_COUNT_ONE_WHEN_EMPTY.spv")});
  }
  for (HashedBackend& bevy : broken) {
    const std::vector<std::vector<TableViolation>> per_frame = violations_of(*bevy.backend);
    EXPECT_TRUE(per_frame[0].empty()) << bevy.name << ": a list that was never empty is right";
    ASSERT_FALSE(per_frame[1].empty()) << bevy.name << ": the checker misses Bevy #21904";
    EXPECT_EQ(per_frame[1][0].invariant, TableInvariant::kOccupiedList) << bevy.name;
    // The entry is what the next list's buffer held: a slot the prune of an earlier frame wrote, or never written.
    EXPECT_NE(per_frame[1][0].ToString().find("entry 0 "), std::string::npos)
        << bevy.name << ": " << per_frame[1][0].ToString();
  }
}

}  // namespace
}  // namespace hpsf::testing
