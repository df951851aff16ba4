// Eviction across frames (core/eviction.h) on all three backends: frame by frame, the hashed tables
// (emulated fast and faithful, Vulkan mapped and staged) evict what the exact map evicts and resolve the same image
// bit for bit, and the table checker passes them from the table before each frame; tombstones keep every live cell
// reachable, and the reclaim that empties every tombstone (D7, in the emulator and as a shader) is caught by the
// checker and the contract; the furnace keeps its light with every policy.

#include "core/eviction.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend.h"
#include "core/error.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "emulated/simt/schedule.h"
#include "property_tests/constructed_cells.h"
#include "property_tests/hashed_backends.h"
#include "property_tests/racing_schedules.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_backend.h"
#include "reference/reference_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/contract_levels.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

using Key = std::array<std::uint32_t, 6>;

constexpr std::uint32_t kSize = 24;
constexpr std::uint32_t kSpp = 2;

std::vector<RecordBatch> TraceFrames(const Scene& scene, std::uint32_t frames) {
  return TracedFrames(scene, kSize, kSpp, frames);
}

std::uint64_t LiveSlots(const HashTableDump& table) {
  std::uint64_t live = 0;
  for (std::size_t s = 0; s < table.capacity; ++s) live += table.tags[s] != kEmptyTag && table.counts[s] > 0;
  return live;
}

TEST(Eviction, ParsesItsPoliciesAndNamesABadOne) {
  EXPECT_EQ(ParseEviction("none"), (Eviction{EvictionPolicy::kNone, 0}));
  EXPECT_EQ(ParseEviction("strict"), (Eviction{EvictionPolicy::kStrict, 1}));
  EXPECT_EQ(ParseEviction("stale:3"), (Eviction{EvictionPolicy::kStale, 3}));
  for (const char* bad : {"stale", "stale:0", "stale:-1", "stale:1048577", "stale:2x", "lru", ""}) {
    try {
      ParseEviction(bad);
      ADD_FAILURE() << bad << " parsed";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--eviction: ", 0), 0u) << e.what();
    }
  }
  const Eviction stale{EvictionPolicy::kStale, 3};
  EXPECT_FALSE(stale.Evicts(5, 3));
  EXPECT_TRUE(stale.Evicts(6, 3));
  EXPECT_FALSE(Eviction{}.Evicts(1000, 0));
  EXPECT_TRUE((Eviction{EvictionPolicy::kStrict, 1}).Evicts(4, 3));
  EXPECT_FALSE((Eviction{EvictionPolicy::kStrict, 1}).Evicts(4, 4));
}

// The animated Cornell box (camera, light and cube move): each frame sees cells the last did not, so both policies
// evict, leave tombstones before live cells and reclaim others.
TEST(Eviction, TheHashedTableEvictsWhatTheExactMapEvictsFrameByFrame) {
  constexpr std::uint32_t kFrames = 6;
  const std::vector<RecordBatch> frames = TraceFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), kFrames);
  for (const char* policy : {"strict", "stale:2"}) {
    for (HashedBackend& hashed : HashedBackends()) {
      const std::string name = hashed.name + ", " + policy;
      FilterConfig config;
      config.capacity = 1u << 12;
      config.frames = kFrames;
      config.eviction = ParseEviction(policy);
      ReferenceBackend reference;
      std::optional<HashTableDump> before;
      std::uint64_t evicted = 0, tombstones = 0, reclaimed = 0;
      for (std::uint32_t k = 0; k < kFrames; ++k) {
        config.frame = k;
        const std::string what = name + ", frame " + std::to_string(k);
        const Image& expected = reference.FilterFrame(frames[k], config);
        const Image& image = hashed.backend->FilterFrame(frames[k], config);
        const HashedRun& run = RunOf(*hashed.backend);
        const std::vector<TableViolation> violations = CheckTable(
            {run.table, frames[k].records, run.keys, run.placements, before ? &*before : nullptr, config.eviction, k});
        EXPECT_TRUE(violations.empty()) << what << ": " << violations.front().ToString();
        ASSERT_EQ(run.probe_failures, 0u) << what;
        EXPECT_EQ(run.evicted, reference.result().stats.cells_evicted) << what;
        EXPECT_EQ(LiveSlots(run.table), reference.result().cells.size()) << what << ": live slots against cells";
        EXPECT_TRUE(image.pixels == expected.pixels) << what << ": image differs from the reference's";
        evicted += run.evicted;
        tombstones += run.tombstones;
        if (before) {
          for (std::size_t s = 0; s < config.capacity; ++s) {
            reclaimed += before->tags[s] != kEmptyTag && before->counts[s] == 0 && run.table.tags[s] == kEmptyTag;
          }
        }
        before = run.table;
      }
      // The oracle is fed: cells were evicted, tombstones were kept before live cells, and some were reclaimed.
      EXPECT_GT(evicted, 100u) << name;
      EXPECT_GT(tombstones, 0u) << name;
      EXPECT_GT(reclaimed + (evicted - tombstones), 0u) << name;
    }
  }
}

// Two cells with one slot0 in a table of 4: A claims slot0 in frame 0, B probes past it to slot0 + 1 in frame 1,
// and strict eviction makes A a tombstone after frame 1, before live B. The right reclaim keeps it; D7's reclaim
// empties it, which the checker sees after frame 1, and in frame 2 B's lookup claims the hole and splits its
// cell, which the comparison with the reference sees.
TEST(Eviction, D7AHoleBeforeALiveCellIsCaughtByTheCheckerAndTheContract) {
  const RecordBatch traced = TraceFrames(LoadScene("cornell"), 1)[0];
  FilterConfig config;
  config.capacity = 4;
  config.probe_limit = 4;
  config.jitter_scale = 0.0f;  // a record's key is the same in every frame
  config.frames = 3;
  config.eviction = ParseEviction("strict");
  const EmulatedRun keyed = EmulatedFilter(traced, config, EmulatorOptions{});
  std::map<Key, std::vector<std::uint32_t>> records_of;
  for (std::uint32_t i = 0; i < keyed.keys.size(); ++i) {
    if (keyed.placements[i] >= config.capacity && keyed.placements[i] != kProbeFailure) continue;
    const shared::KeyWords& w = keyed.keys[i].words;
    records_of[{w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra}].push_back(i);
  }
  std::optional<Key> a, b;
  for (auto i = records_of.begin(); i != records_of.end() && !b; ++i) {
    for (auto j = std::next(i); j != records_of.end(); ++j) {
      const KeyResult& ki = keyed.keys[i->second[0]];
      const KeyResult& kj = keyed.keys[j->second[0]];
      if (ki.slot0 == kj.slot0 && ki.fingerprint != kj.fingerprint) {
        a = i->first, b = j->first;
        break;
      }
    }
  }
  ASSERT_TRUE(a && b) << "no two cells share a slot0 among " << records_of.size();
  // A frame holding only one cell's records: the others keep their pixels but lose their vertex.
  auto only = [&](const Key& key) {
    RecordBatch batch = traced;
    std::vector<bool> keep(batch.records.size(), false);
    for (std::uint32_t i : records_of[key]) keep[i] = true;
    for (std::size_t i = 0; i < batch.records.size(); ++i) {
      if (!keep[i]) batch.records[i].path.z &= ~shared::kRecordHasVertex;
    }
    return batch;
  };
  // Frame 2: B's records again, twice as bright, so B's cell over frames 1 and 2 averages otherwise than frame 2's
  // records alone (a cell split by D7's hole).
  RecordBatch brighter = only(*b);
  for (std::uint32_t i : records_of[*b]) brighter.records[i].contribution *= glm::vec4(2.0f, 2.0f, 2.0f, 1.0f);
  const std::vector<RecordBatch> frames = {only(*a), only(*b), brighter};
  const std::uint32_t slot0 = keyed.keys[records_of[*a][0]].slot0;

  struct Outcome {
    std::map<TableInvariant, int> violations;  // over all frames
    bool image_differs = false;                // from the reference's, in some frame
  };
  auto run_sequence = [&](Backend& hashed) {
    Outcome outcome;
    ReferenceBackend reference;
    std::optional<HashTableDump> before;
    for (std::uint32_t k = 0; k < frames.size(); ++k) {
      config.frame = k;
      const Image& expected = reference.FilterFrame(frames[k], config);
      outcome.image_differs |= hashed.FilterFrame(frames[k], config).pixels != expected.pixels;
      const HashedRun& run = RunOf(hashed);
      if (k == 1) {
        EXPECT_EQ(run.placements[records_of[*b][0]], (slot0 + 1) % 4) << "B probed past A";
      }
      for (const TableViolation& v : CheckTable({run.table, frames[k].records, run.keys, run.placements,
                                                 before ? &*before : nullptr, config.eviction, k})) {
        ++outcome.violations[v.invariant];
      }
      before = run.table;
    }
    return outcome;
  };
  for (HashedBackend& hashed : HashedBackends()) {
    const Outcome right = run_sequence(*hashed.backend);
    EXPECT_TRUE(right.violations.empty()) << hashed.name;
    EXPECT_FALSE(right.image_differs) << hashed.name;
  }
  for (HashedBackend& hashed : HashedBackends(D7ReclaimEveryTombstone, HPSF_SHADER_VARIANT_DIR "/eviction_D7.spv")) {
    Outcome d7 = run_sequence(*hashed.backend);
    EXPECT_GT(d7.violations[TableInvariant::kHoleBeforeLiveSlot], 0) << hashed.name << ": the checker misses D7's hole";
    EXPECT_TRUE(d7.image_differs) << hashed.name << ": the contract misses D7's split cell";
  }
}

// The sequence the racing eviction is judged on: 2 frames of the animated Cornell box, 512 slots (crowded, so the
// frames share slots), strict eviction.
struct RacingSequence {
  std::vector<RecordBatch> frames = TraceFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), 2);
  std::vector<std::uint32_t> numbers = {0, 1};
  FilterConfig config = [] {
    FilterConfig c;
    c.capacity = 512;
    c.probe_limit = 8;
    c.frames = 2;
    c.eviction = ParseEviction("strict");
    return c;
  }();
};

// An eviction racing an insertion (EvictDuringAccumulate: thread i evicts slot i by the policy, then inserts its
// record, in one launch). Over 2 frames of the animated Cornell box in a crowded table with strict eviction, the
// faithful emulator explores interleavings of the evictions and the insertions under 40 schedules (random and PCT
// of depth 3, warps of 4) and fast mode's serial order (one worker thread); the contract over the sequence (the
// table checker from the table before frame 1, and the reference) must catch the variant under at least one, and
// the correct kernel, whose eviction is a pass of its own after the accumulate, must pass under every one.
TEST(Eviction, AnEvictionRacingAnInsertionIsCaughtUnderTheSchedulesThatInterleaveThem) {
  const RacingSequence sequence;
  const auto& [frames, numbers, config] = sequence;
  const std::vector<EmulatorOptions> schedules = RacingSchedules();
  auto passes = [&](const EmulatorOptions& options, AccumulateKernelFn kernel, std::string* failure) {
    EmulatedBackend backend(options, kernel), rerun(options, kernel);
    const JudgedBackend judged{"emulated", &backend, &rerun, "rerun", options.mode == simt::Mode::kFaithful, false};
    const CrosscheckReport report = JudgeSequence(frames, numbers, config, std::span<const JudgedBackend>(&judged, 1));
    *failure = report.FirstFailure();
    return report.Passed();
  };
  int caught = 0;
  for (const EmulatorOptions& options : schedules) {
    const std::string name = options.mode == simt::Mode::kFast ? "fast, one thread" : options.schedule;
    std::string failure;
    EXPECT_TRUE(passes(options, AccumulateKernel, &failure)) << name << ": " << failure;
    if (!passes(options, EvictDuringAccumulate, &failure)) {
      if (caught++ == 0) std::printf("eviction racing insertion, %s: %s\n", name.c_str(), failure.c_str());
    }
  }
  std::printf("eviction racing insertion: caught under %d of %zu schedules\n", caught, schedules.size());
  EXPECT_GT(caught, 0) << "no schedule let an eviction race an insertion";
}

// The same variant as a user's accumulate shader (accumulate_EVICT_RACE.spv: the invocation of record i evicts
// slot i by strict's rule before inserting), through the stable buffer interface over 2 frames, mapped and staged:
// the contract over the sequence fails it; the correct shader given the same way passes.
TEST(Eviction, AnEvictionRacingAnInsertionAsAShaderFailsTheContract) {
  const RacingSequence sequence;
  const auto& [frames, numbers, config] = sequence;
  for (const StagingPolicy staging : kStagingPolicies) {
    for (const char* variant : {"correct", "EVICT_RACE"}) {
      const std::string spv = std::string(HPSF_SHADER_VARIANT_DIR "/accumulate_") + variant + ".spv";
      VulkanBackend backend(TestDevice(staging), spv), rerun(TestDevice(staging), spv);
      const JudgedBackend judged{"vulkan", &backend, &rerun, "rerun", false, true};
      const CrosscheckReport report =
          JudgeSequence(frames, numbers, config, std::span<const JudgedBackend>(&judged, 1));
      const std::string name = std::string(variant) + ", staging " + ToString(staging);
      const bool correct = std::string(variant) == "correct";
      EXPECT_EQ(report.Passed(), correct) << name;
      if (!report.Passed()) std::printf("%s: %s\n", name.c_str(), report.FirstFailure().c_str());
    }
  }
}

// Every interleaving of one eviction and one insertion into the same slot, enumerated. Cell A (slot0 = 0 in a
// table of 4 slots) is placed in frame 0; frame 1 holds a record without a vertex (thread 0, which in the racing
// variant evicts slot 0) and a record of A (thread 1, which touches slot 0), so strict eviction must keep A. The
// exhaustive schedule (warps of one lane) enumerates every order of the two threads' operations. The variant loses
// A (evicted whole, or its history zeroed under the new record) wherever thread 0 reads slot 0's last-seen frame
// before thread 1 stores it, which is most orders (thread 1 stores it after its four adds); a few orders keep A.
// The correct kernel passes every order.
TEST(Eviction, EveryInterleavingOfAnEvictionWithAnInsertionIntoItsSlotIsExplored) {
  FilterConfig config = ConstructedConfig(4, 4);
  config.frames = 2;
  config.eviction = ParseEviction("strict");
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 0u; });
  const RecordBatch frame0 = BatchOfCells({a});
  RecordBatch frame1 = BatchOfCells({a, a});
  frame1.frame = 1;
  frame1.records[0].path.z &= ~shared::kRecordHasVertex;
  const EmulatedRun first = EmulatedFilter(frame0, config, EmulatorOptions{});
  config.frame = 1;
  auto explore = [&](AccumulateKernelFn kernel) {
    return ExploreEveryOrder(EmulatorOptions{}, [&](const EmulatorOptions& each) {
      const EmulatedRun run = EmulatedFilter(frame1, config, each, kernel, &first.table);
      return !CheckTable({run.table, frame1.records, run.keys, run.placements, &first.table, config.eviction, 1})
                  .empty();
    });
  };
  const Exploration correct = explore(AccumulateKernel);
  const Exploration racing = explore(EvictDuringAccumulate);
  std::printf(
      "one eviction and one insertion, exhaustive: correct kernel %llu schedules, all pass; racing variant "
      "caught under %llu of %llu\n",
      (unsigned long long)correct.schedules, (unsigned long long)racing.caught, (unsigned long long)racing.schedules);
  EXPECT_EQ(correct.caught, 0u);
  EXPECT_GT(racing.caught, 0u);
  EXPECT_LT(racing.caught, racing.schedules) << "every order lost A: the exploration saw no order that keeps it";
}

double MeanRadiance(const Image& image) {
  double sum = 0;
  for (const glm::vec3& p : image.pixels) sum += double(p.x) + p.y + p.z;
  return sum / (3.0 * double(image.pixels.size()));
}

// The furnace's radiance is the same everywhere: with a moving camera over 16 frames, every policy and temporal
// mode keeps the light on every backend (priority in a table of 256 slots, under pressure), frame by frame: each
// frame's filtered mean stays within 1% of the same records' unfiltered mean (plain path tracing), and no pixel is
// poisoned. Measured: at most 0.52% on every backend, policy and mode, none and integrate included (the filter's own
// noise at 24 x 24 x 2 spp). A frame that read evicted cells (0 / 0) would be NaN; one whose table forgot the light
// would fall by its share of the records.
TEST(Eviction, TheFurnaceKeepsItsLightOver16FramesOfAMovingCamera) {
  constexpr std::uint32_t kFrames = 16;
  Scene furnace = LoadScene("furnace");
  furnace.animation.camera = {{0, {-0.4, 0.0, -0.9}, {-0.4, 0.0, 1.0}}, {15, {0.4, 0.2, -0.9}, {0.4, 0.2, 1.0}}};
  const std::vector<RecordBatch> frames = TraceFrames(furnace, kFrames);
  struct Case {
    const char* policy;
    const char* temporal;
  };
  for (const auto& [policy, temporal] :
       {Case{"none", "integrate"}, Case{"strict", "integrate"}, Case{"stale:4", "integrate"}, Case{"none", "ema:0.8"},
        Case{"strict", "ema:1:8"}, Case{"stale:4", "adaptive"}, Case{"priority", "integrate"}}) {
    FilterConfig config;
    config.capacity = 1u << 12;
    if (std::string(policy) == "priority") {  // a table under pressure, so priority evicts
      config.capacity = 256;
      config.fingerprint_bits = 24;
    }
    config.frames = kFrames;
    config.eviction = ParseEviction(policy);
    config.temporal = ParseTemporal(temporal);
    std::vector<HashedBackend> backends = HashedBackends();
    backends.push_back({"reference", std::make_unique<ReferenceBackend>()});
    for (HashedBackend& b : backends) {
      double worst = 0;
      for (std::uint32_t k = 0; k < kFrames; ++k) {
        config.frame = k;
        const double filtered = MeanRadiance(b.backend->FilterFrame(frames[k], config));
        ASSERT_TRUE(std::isfinite(filtered)) << b.name << ", " << policy << ", " << temporal << ", frame " << k;
        const double unfiltered = MeanRadiance(UnfilteredImage(frames[k]));
        ASSERT_GT(unfiltered, 1.9) << "the furnace's light";
        worst = std::max(worst, std::abs(filtered / unfiltered - 1.0));
      }
      EXPECT_LT(worst, 0.01) << b.name << ", " << policy << ", " << temporal;
      std::printf("%s, %s, %s: worst |filtered / unfiltered - 1| over %u frames %.2e\n", b.name.c_str(), policy,
                  temporal, kFrames, worst);
    }
  }
}

}  // namespace
}  // namespace hpsf::testing
