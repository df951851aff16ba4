// Multi-level accumulation (--levels, --min-count; core/shared/levels.h; Binder et al. §3.3.2): every backend agrees
// with the reference on every scene, one frame and sequences, roomy and crowded tables; a coarser cell holds exactly
// its children's samples; the resolve reads the finest level whose count reaches the threshold; and the broken
// variants (coarser cells keyed unjittered, in the emulator and as a shader; a resolve that judges every level by the
// own cell's count) fail the contract. Label `levels`.

#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "emulated/emulated_filter.h"
#include "property_tests/constructed_cells.h"
#include "property_tests/crosscheck_report_figures.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_filter.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/crosscheck.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf::testing {
namespace {

const std::vector<std::string> kAllBackends = {"reference", "emulated", "vulkan"};

// The Cornell box and the furnace, one frame and three of the animated box (ema blending, stale eviction), in a roomy
// table and a crowded one (probe failures and 8-bit aliases at every level), in each accumulation: every level of
// the contract passes on all three backends. Roomy fixed64 holds nothing classified, so level 3 held every image to
// the reference's, bit for bit.
TEST(MultiLevel, EveryBackendAgreesWithTheReferenceOnEveryScene) {
  const std::vector<RecordBatch> cornell = {TracedBatch("cornell", 24, 4)};
  const std::vector<RecordBatch> furnace = {TracedBatch(HPSF_SCENES_DIR "/furnace.json", 24, 4)};
  const std::vector<RecordBatch> animated = TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), 24, 2, 3);
  Crosschecker checker(kAllBackends);
  struct Scene {
    const char* name;
    const std::vector<RecordBatch>* frames;
  };
  for (const Scene& scene : {Scene{"cornell", &cornell}, Scene{"furnace", &furnace}, Scene{"animated", &animated}}) {
    for (const bool crowded : {false, true}) {
      for (const Accumulation accumulation :
           {Accumulation::kFixed64, Accumulation::kFloat32, Accumulation::kPackedDecimal}) {
        for (const std::uint32_t levels : {2u, 3u}) {
          FilterConfig config;
          config.levels = levels;
          config.min_count = 4;
          config.accumulation = accumulation;
          config.capacity = crowded ? 1u << 8 : 1u << 14;
          config.probe_limit = crowded ? 4 : 16;
          config.fingerprint_bits = crowded ? 8 : 32;
          config.frames = std::uint32_t(scene.frames->size());
          if (config.frames > 1) {
            config.temporal = ParseTemporal("ema:0.5");
            config.eviction = ParseEviction("stale:1");
          }
          const std::string name = std::string(scene.name) + (crowded ? ", crowded, " : ", roomy, ") +
                                   ToString(accumulation) + ", levels " + std::to_string(levels);
          const CrosscheckReport report = checker.CheckFrames(*scene.frames, config, EmulatorOptions{});
          EXPECT_TRUE(report.Passed()) << name << ": " << report.FirstFailure();
          for (int level = 1; level <= 4; ++level) EXPECT_TRUE(Level(report, level).applicable) << name;
          for (const char* backend : {"emulated", "vulkan"}) {
            const QualityFigures& q = QualityOf(report, backend);
            if (crowded) {
              EXPECT_GT(q.probe_failures + q.aliased_slots, 0u) << name << ", " << backend << ": nothing crowded";
            } else {
              EXPECT_EQ(q.probe_failures + q.aliased_slots, 0u) << name << ", " << backend;
            }
          }
        }
      }
    }
  }
}

// Across a dolly (the camera moves, so records change level), with resolution changes seeding new cells at every
// level, with compaction listing every level's slots, both in packed-decimal, and priority eviction in a table under
// pressure (coarser touches that found no slot choose victims too): the contract holds on all three backends frame
// by frame, the seed pass seeded coarser cells, and the priority case evicted.
TEST(MultiLevel, LevelsRunWithResolutionChangesAndCompaction) {
  const std::vector<RecordBatch> frames = TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-dolly.json"), 32, 2, 4);
  Crosschecker checker(kAllBackends);
  struct Case {
    const char* name;
    const char* level_change;
    Compaction compaction;
    Accumulation accumulation;
    const char* eviction = "stale:1";
    std::uint32_t capacity = 1u << 14;
  };
  for (const Case& c :
       {Case{"seed", "seed:1", Compaction::kNone, Accumulation::kFixed64},
        Case{"compacted", "none", Compaction::kOccupiedList, Accumulation::kFixed64},
        Case{"seed, compacted, packed", "seed", Compaction::kOccupiedList, Accumulation::kPackedDecimal},
        Case{"seed, float32", "seed", Compaction::kNone, Accumulation::kFloat32},
        Case{"priority", "none", Compaction::kNone, Accumulation::kFixed64, "priority", 256}}) {
    FilterConfig config;
    config.levels = 3;
    config.min_count = 4;
    config.capacity = c.capacity;
    config.frames = 4;
    config.fingerprint_bits = 24;  // priority's tombstone tag is 0xFFFFFFFF
    config.level_seed = ParseLevelSeed(c.level_change);
    config.compaction = c.compaction;
    config.accumulation = c.accumulation;
    config.eviction = ParseEviction(c.eviction);
    config.temporal = ParseTemporal("ema:0.5");
    const CrosscheckReport report = checker.CheckFrames(frames, config, EmulatorOptions{});
    EXPECT_TRUE(report.Passed()) << c.name << ": " << report.FirstFailure();
    if (config.eviction.by_priority()) {
      EmulatedBackend emulated{EmulatorOptions{}};
      std::uint64_t evicted = 0, coarser_failures = 0;
      for (const RecordBatch& frame : frames) {
        config.frame = frame.frame;
        emulated.FilterFrame(frame, config);
        evicted += emulated.run().evicted;
        for (const std::uint32_t slot : emulated.run().coarser_placements) coarser_failures += slot == kProbeFailure;
      }
      EXPECT_GT(evicted, 0u) << c.name;
      EXPECT_GT(coarser_failures, 0u) << c.name;
    }
    if (!config.level_seed.enabled) continue;
    // Cells seeded at a coarser level: a slot placed only by coarser touches that the seed pass marked.
    EmulatedBackend emulated{EmulatorOptions{}};
    std::uint64_t coarser_seeded = 0;
    for (const RecordBatch& frame : frames) {
      config.frame = frame.frame;
      emulated.FilterFrame(frame, config);
      const EmulatedRun& run = emulated.run();
      std::vector<bool> own(config.capacity, false);
      for (const std::uint32_t slot : run.placements) {
        if (slot < config.capacity) own[slot] = true;
      }
      for (const std::uint32_t slot : run.coarser_placements) {
        coarser_seeded += slot < config.capacity && !own[slot] && !run.seeded_slots.empty() && run.seeded_slots[slot];
      }
    }
    EXPECT_GT(coarser_seeded, 0u) << c.name;
  }
}

// With level of detail off every record's own cell is at one level, so a coarser cell holds exactly the samples of
// its children: its count and fixed64 sums are theirs added, in the reference's exact map and in both hashed tables
// (found by the tables' own placements, not by the checker).
TEST(MultiLevel, ACoarserCellHoldsExactlyItsChildrensSamples) {
  const RecordBatch batch = TracedBatch("cornell", 32, 4);
  FilterConfig config;
  config.lod = false;
  config.cell_size = 0.0625f;
  config.levels = 3;
  config.capacity = 1u << 18;
  const FilterResult reference = ReferenceFilter(batch, config);
  const EmulatedRun emulated = EmulatedFilter(batch, config, EmulatorOptions{});
  VulkanFilter vulkan_filter(TestDevice(StagingPolicy::kNever));
  const VulkanRun vulkan = vulkan_filter.Run(batch, config);
  const std::size_t n = batch.records.size();
  struct Table {
    const char* name;
    std::function<std::uint32_t(std::size_t, std::uint32_t)> placement;  // record, level -> cell or slot
    std::function<std::uint64_t(std::uint32_t)> count;
    std::function<std::array<std::uint64_t, 3>(std::uint32_t)> sums;
    std::uint32_t cells;  // of the exact map, or slots
  };
  const std::vector<Table> tables = {
      {"reference",
       [&](std::size_t i, std::uint32_t k) {
         return k == 0 ? reference.placement[i] : reference.coarser_placement[(k - 1) * n + i];
       },
       [&](std::uint32_t c) { return reference.cells[c].count; },
       [&](std::uint32_t c) { return reference.cells[c].fixed_sum; }, std::uint32_t(reference.cells.size())},
      {"emulated", [&](std::size_t i, std::uint32_t k) { return LevelPlacement(emulated, i, k); },
       [&](std::uint32_t s) { return emulated.table.counts[s]; },
       [&](std::uint32_t s) { return emulated.table.fixed_sums[s]; }, config.capacity},
      {"vulkan", [&](std::size_t i, std::uint32_t k) { return LevelPlacement(vulkan, i, k); },
       [&](std::uint32_t s) { return vulkan.table.counts[s]; },
       [&](std::uint32_t s) { return vulkan.table.fixed_sums[s]; }, config.capacity},
  };
  for (const Table& table : tables) {
    std::uint64_t parents = 0;
    for (std::uint32_t k = 1; k < config.levels; ++k) {
      std::map<std::uint32_t, std::set<std::uint32_t>> children;  // parent -> its children's cells or slots
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t parent = table.placement(i, k), child = table.placement(i, k - 1);
        if (parent == kNoCell) continue;  // no vertex, rejected or unkeyable (and kNotPlaced in a hashed table)
        ASSERT_LT(std::max(parent, child), table.cells)
            << table.name << ": record " << i << ", level " << k << ": " << parent << " over " << child;
        children[parent].insert(child);
      }
      for (const auto& [parent, cells] : children) {
        std::uint64_t count = 0;
        std::array<std::uint64_t, 3> sums{};
        for (const std::uint32_t child : cells) {
          count += table.count(child);
          for (int c = 0; c < 3; ++c) sums[c] += table.sums(child)[c];
        }
        EXPECT_EQ(table.count(parent), count) << table.name << ": level " << k << " cell " << parent;
        EXPECT_EQ(table.sums(parent), sums) << table.name << ": level " << k << " cell " << parent;
        EXPECT_LE(cells.size(), 8u) << table.name;
        ++parents;
      }
    }
    EXPECT_GT(parents, 100u) << table.name;
  }
}

// The checker's nesting invariant names a coarser slot that lost one of its children's adds (a count and a sum
// taken away, as a lost atomic would), beside the per-slot counts.
TEST(MultiLevel, TheCheckerNamesACoarserCellThatLostAChildsAdd) {
  const RecordBatch batch = TracedBatch("cornell", 24, 4);
  FilterConfig config;
  config.levels = 2;
  config.capacity = 1u << 14;
  EmulatedRun run = EmulatedFilter(batch, config, EmulatorOptions{});
  auto check = [&] {
    TableCheckInput input{run.table, batch.records, run.keys, run.placements};
    input.coarser_placements = run.coarser_placements;
    return CheckTable(input);
  };
  ASSERT_TRUE(check().empty()) << check().front().ToString();
  std::uint32_t parent = kNotPlaced;
  for (const std::uint32_t slot : run.coarser_placements) {
    if (slot < config.capacity && run.table.counts[slot] > 1) parent = slot;
  }
  ASSERT_NE(parent, kNotPlaced);
  run.table.counts[parent] -= 1;
  run.table.fixed_sums[parent][0] -= 1;
  bool nesting = false;
  for (const TableViolation& v : check()) nesting |= v.invariant == TableInvariant::kLevelNesting && v.slot == parent;
  EXPECT_TRUE(nesting) << "the nesting invariant did not name slot " << parent;
}

// Cells (0,0,0) with one record, (1,0,0) with three and (0,1,0) with one: their parent (0,0,0) one level up holds
// all five. With --min-count 3, (1,0,0)'s records read their own cell (its count reaches 3), the other two fall back
// to the parent; with --min-count 6 nothing reaches it and every record reads its coarsest level. Every backend
// chooses so, and its pixel is the chosen cell's average.
TEST(MultiLevel, TheResolveReadsTheFinestLevelWhoseCountReachesTheThreshold) {
  const RecordBatch batch = BatchOfCells({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  FilterConfig config = ConstructedConfig(64, 8);
  config.levels = 2;
  VulkanFilter vulkan_filter(TestDevice(StagingPolicy::kNever));
  for (const std::uint32_t min_count : {3u, 6u}) {
    config.min_count = min_count;
    const FilterResult reference = ReferenceFilter(batch, config);
    const EmulatedRun emulated = EmulatedFilter(batch, config, EmulatorOptions{});
    const VulkanRun vulkan = vulkan_filter.Run(batch, config);
    const std::vector<std::uint64_t> expected =
        min_count == 3 ? std::vector<std::uint64_t>{3, 2} : std::vector<std::uint64_t>{0, 5};
    EXPECT_EQ(reference.stats.resolved_at_level, expected) << min_count;
    EXPECT_EQ(emulated.resolved_at_level, expected) << min_count;
    EXPECT_EQ(vulkan.resolved_at_level, expected) << min_count;
    // Record 0's value: radiance_before 0 + throughput 0.5 * the parent's average of the five contributions.
    double parent_red = 0.0;
    for (const Record& r : batch.records) parent_red += r.contribution.x;
    const float expected_red = float(0.5 * (parent_red / 5.0));
    for (const Image* image : {&reference.image, &emulated.image, &vulkan.image}) {
      EXPECT_EQ(image->pixels[0].x, expected_red) << min_count;
    }
  }
}

// --levels 2 with --min-count 1 reads every record's own cell. With level of detail off no record's own cell is
// another's coarser one, so that is the image of one level, bit for bit, on every backend. (Under level of detail a
// record whose own level is l + 1 shares its cell with the coarser level of records at l: the cell holds every
// sample in its volume, and its average moves.)
TEST(MultiLevel, AThresholdOfOneReadsTheOwnCellAsOneLevelDoes) {
  const RecordBatch batch = TracedBatch("cornell", 24, 4);
  FilterConfig one;
  one.lod = false;
  one.cell_size = 0.125f;
  one.capacity = 1u << 16;
  FilterConfig two = one;
  two.levels = 2;
  VulkanFilter vulkan_filter(TestDevice(StagingPolicy::kNever));
  EXPECT_TRUE(SameBits(ReferenceFilter(batch, one).image, ReferenceFilter(batch, two).image));
  EXPECT_TRUE(SameBits(EmulatedFilter(batch, one, {}).image, EmulatedFilter(batch, two, {}).image));
  const Image vulkan_one = vulkan_filter.Run(batch, one).image;
  EXPECT_TRUE(SameBits(vulkan_one, vulkan_filter.Run(batch, two).image));
}

// Each broken variant fails the contract: coarser cells keyed at the unjittered position (emulator kernel and
// shader: level 2, the slot is not among the derived key's candidates), and a resolve that judges every level by
// the count of the record's own cell (shader and emulator resolve; level 3: the image is not the reference's).
TEST(MultiLevel, EachBrokenVariantFailsTheContract) {
  const std::vector<RecordBatch> frames = {TracedBatch("cornell", 24, 4)};
  FilterConfig config;
  config.levels = 3;
  config.min_count = 4;
  config.capacity = 1u << 14;
  const std::string variants = HPSF_SHADER_VARIANT_DIR;
  VulkanBackendOptions unjittered, wrong_count;
  unjittered.accumulate_spv = variants + "/accumulate_LEVEL_UNJITTERED.spv";
  wrong_count.resolve_spv = variants + "/resolve_LEVEL_WRONG_COUNT.spv";
  struct Variant {
    const char* name;
    std::vector<std::string> backends;
    Defect defect;
    VulkanBackendOptions vulkan;
    int level;
  };
  const std::vector<Variant> cases = {
      {"emulator kernel level-unjittered", {"reference", "emulated"}, Defect::kLevelUnjittered, {}, 2},
      {"shader LEVEL_UNJITTERED", {"reference", "vulkan"}, Defect::kNone, unjittered, 2},
      {"resolve LEVEL_WRONG_COUNT", {"reference", "vulkan"}, Defect::kNone, wrong_count, 3},
      {"emulated resolve level-wrong-count", {"reference", "emulated"}, Defect::kLevelWrongCount, {}, 3},
  };
  for (const Variant& v : cases) {
    const CrosscheckReport report = Crosschecker(v.backends, v.defect, v.vulkan).CheckFrames(frames, config, {});
    EXPECT_FALSE(Level(report, v.level).passed) << v.name << " escaped level " << v.level;
    std::printf("%s: %s\n", v.name, report.FirstFailure().c_str());
  }
}

// Options: a bad value names its option.
TEST(MultiLevel, ABadLevelsOrThresholdNamesItsOption) {
  auto error_of = [](FilterConfig c) -> std::string {
    try {
      c.Validate();
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  FilterConfig c;
  c.levels = 0;
  EXPECT_NE(error_of(c).find("--levels"), std::string::npos);
  c.levels = 9;
  EXPECT_NE(error_of(c).find("--levels"), std::string::npos);
  c.levels = 1;
  c.min_count = 0;
  EXPECT_NE(error_of(c).find("--min-count"), std::string::npos);
  c.min_count = 2;
  EXPECT_NE(error_of(c).find("needs --levels 2 or more"), std::string::npos);
  c.levels = 2;
  EXPECT_EQ(error_of(c), "");
  c.compaction = Compaction::kOccupiedList;
  c.level_seed = ParseLevelSeed("seed");
  c.eviction = ParseEviction("priority");
  c.fingerprint_bits = 24;
  EXPECT_EQ(error_of(c), "");
}

}  // namespace
}  // namespace hpsf::testing
