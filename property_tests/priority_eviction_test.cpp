// Priority eviction (core/eviction.h, Binder et al. §3.4.3) on every hashed backend: in a table under
// pressure, the record that found no slot makes the untouched cell of lowest priority in its window a claimable
// tombstone and finds room the next frame; the table checker recomputes every victim from the table before the
// frame and the frame's placements, and catches the compare of the wrong sign in the emulator and as a shader; the
// contract over a sequence holds where the exact map, which has no pressure, keeps what the table evicted.

#include <cstdint>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/eviction.h"
#include "core/shared/eviction_priority.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "property_tests/constructed_cells.h"
#include "property_tests/hashed_backends.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "tracer/scene_file.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/contract_levels.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

const std::string kWrongSignShader = HPSF_SHADER_VARIANT_DIR "/eviction_PRIORITY_SIGN.spv";

std::vector<TableViolation> CheckFrame(const HashedRun& run, const RecordBatch& batch,
                                       const std::optional<HashTableDump>& before, const FilterConfig& config) {
  return CheckTable(
      {run.table, batch.records, run.keys, run.placements, before ? &*before : nullptr, config.eviction, config.frame});
}

// The animated Cornell box in a table too small for it: 256 slots, probes of 8, 24-bit fingerprints, priority
// eviction; every frame some records find no slot.
struct PressuredSequence {
  explicit PressuredSequence(std::uint32_t frame_count)
      : frames(TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), 24, 2, frame_count)) {
    for (const RecordBatch& frame : frames) numbers.push_back(frame.frame);
    config.capacity = 256;
    config.probe_limit = 8;
    config.fingerprint_bits = 24;
    config.frames = frame_count;
    config.eviction = ParseEviction("priority");
  }
  std::vector<RecordBatch> frames;
  std::vector<std::uint32_t> numbers;
  FilterConfig config;
};

TEST(PriorityEviction, ParsesAndReservesATagOfTheFingerprint) {
  EXPECT_EQ(ParseEviction("priority"), (Eviction{EvictionPolicy::kPriority, 0}));
  EXPECT_EQ(ParseEviction("priority").ToString(), "priority");
  EXPECT_FALSE(ParseEviction("priority").Evicts(1000, 0)) << "priority evicts by pressure, never by age";
  FilterConfig config;
  config.eviction = ParseEviction("priority");
  config.fingerprint_bits = 32;
  try {
    config.Validate();
    ADD_FAILURE() << "priority with 32-bit fingerprints validated: a fingerprint could equal the tombstone tag";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--eviction: ", 0), 0u) << e.what();
  }
  config.fingerprint_bits = 31;
  EXPECT_NO_THROW(config.Validate());
  // Least recently seen first, then fewest samples, then the lower tag.
  EXPECT_TRUE(shared::EvictedBefore(shared::EvictionPriority(3, 100), 9, shared::EvictionPriority(4, 1), 1));
  EXPECT_TRUE(shared::EvictedBefore(shared::EvictionPriority(4, 1), 9, shared::EvictionPriority(4, 2), 1));
  EXPECT_TRUE(shared::EvictedBefore(shared::EvictionPriority(4, 1), 1, shared::EvictionPriority(4, 1), 9));
  EXPECT_FALSE(shared::EvictedBefore(shared::EvictionPriority(4, 1), 9, shared::EvictionPriority(4, 1), 9));
  EXPECT_EQ(shared::EvictionPriority(0, ~std::uint64_t(0)), 0xFFFFFFFFull) << "the count saturates below the frame";
}

// Five constructed cells in a table of 4 slots (every window is the whole table). Frame 0: A, B. Frame 1: C, D twice,
// A. Frame 2: E finds no slot, so the victim is B (last seen in frame 0); the wrong sign evicts A or D (seen in
// frame 1, two samples). Frame 3: E claims B's tombstone. Every frame passes the checker on every backend; the
// wrong sign fails it after frame 2 with the policy's invariant.
TEST(PriorityEviction, TheLowestPriorityIsEvictedAndItsTombstoneClaimed) {
  FilterConfig config = ConstructedConfig(4, 4, 24);
  config.frames = 4;
  config.eviction = ParseEviction("priority");
  std::vector<glm::ivec3> cells;
  std::set<std::uint32_t> fingerprints;
  for (int start = 0; cells.size() < 5; start += 1000) {
    const glm::ivec3 cell = FindCell(
        config, [](const KeyResult&) { return true; }, start);
    if (fingerprints.insert(KeyOfCell(config, cell).fingerprint).second) cells.push_back(cell);
  }
  const glm::ivec3 a = cells[0], b = cells[1], c = cells[2], d = cells[3], e = cells[4];
  std::vector<RecordBatch> frames = {BatchOfCells({a, b}), BatchOfCells({c, d, d, a}), BatchOfCells({e}),
                                     BatchOfCells({e})};
  for (std::uint32_t k = 0; k < frames.size(); ++k) frames[k].frame = k;
  auto slot_of = [&](const HashedRun& run, std::uint32_t record) { return run.placements[record]; };

  for (HashedBackend& hashed : HashedBackends()) {
    std::optional<HashTableDump> before;
    std::uint32_t slot_b = 0;
    for (std::uint32_t k = 0; k < frames.size(); ++k) {
      config.frame = k;
      const std::string what = hashed.name + ", frame " + std::to_string(k);
      hashed.backend->FilterFrame(frames[k], config);
      const HashedRun& run = RunOf(*hashed.backend);
      const std::vector<TableViolation> violations = CheckFrame(run, frames[k], before, config);
      EXPECT_TRUE(violations.empty()) << what << ": " << violations.front().ToString();
      if (k == 0) slot_b = slot_of(run, 1);
      if (k == 2) {
        EXPECT_EQ(run.placements[0], kProbeFailure) << what << ": E found a slot in a full table";
        EXPECT_EQ(run.evicted, 1u) << what;
        EXPECT_EQ(run.table.tags[slot_b], shared::kTombstoneTag) << what << ": B's slot is not a tombstone";
        EXPECT_EQ(run.table.counts[slot_b], 0u) << what;
      }
      if (k == 3) {
        EXPECT_EQ(slot_of(run, 0), slot_b) << what << ": E did not claim B's tombstone";
      }
      before = run.table;
    }
  }
  for (HashedBackend& hashed :
       HashedBackends(EvictionKernels(ReclaimKernel, SelectVictimsWrongSign), kWrongSignShader)) {
    std::optional<HashTableDump> before;
    std::map<TableInvariant, int> violations;
    for (std::uint32_t k = 0; k < 3; ++k) {
      config.frame = k;
      hashed.backend->FilterFrame(frames[k], config);
      for (const TableViolation& v : CheckFrame(RunOf(*hashed.backend), frames[k], before, config)) {
        ++violations[v.invariant];
        if (k == 2 && violations[v.invariant] == 1)
          std::printf("%s, wrong sign: %s\n", hashed.name.c_str(), v.ToString().c_str());
      }
      before = RunOf(*hashed.backend).table;
    }
    EXPECT_EQ(violations[TableInvariant::kEvictionPolicy], 2) << hashed.name << ": B kept and A or D evicted";
  }
}

// Priority's insertion looks for its cell only up to the first empty slot of its window: beyond it, a slot with
// the same fingerprint is another cell's whose fingerprint aliases (8-bit fingerprints here), never its own. A and
// B are cells with one fingerprint, B's slot0 two past A's. B is filtered in frame 0; in frame 1 A finds slot0
// empty and claims it on every backend. A look that ran on past the empty slot would join B's cell: the checker
// names that placement (an empty slot earlier in its window) and A's slot and count show it.
TEST(PriorityEviction, ACellIsLookedForOnlyUpToTheFirstEmptySlotWhenFingerprintsAlias) {
  FilterConfig config = ConstructedConfig(1024, 8, 8);
  config.frames = 2;
  config.eviction = ParseEviction("priority");
  const glm::ivec3 a = FindCell(config, [](const KeyResult&) { return true; });
  const KeyResult key_a = KeyOfCell(config, a);
  const glm::ivec3 b = FindCell(
      config,
      [&](const KeyResult& k) {
        return k.fingerprint == key_a.fingerprint && k.slot0 == ((key_a.slot0 + 2u) & (config.capacity - 1u));
      },
      1);
  std::vector<RecordBatch> frames = {BatchOfCells({b}), BatchOfCells({a})};
  for (std::uint32_t k = 0; k < frames.size(); ++k) frames[k].frame = k;
  for (HashedBackend& hashed : HashedBackends()) {
    std::optional<HashTableDump> before;
    for (std::uint32_t k = 0; k < frames.size(); ++k) {
      config.frame = k;
      const std::string what = hashed.name + ", frame " + std::to_string(k);
      hashed.backend->FilterFrame(frames[k], config);
      const HashedRun& run = RunOf(*hashed.backend);
      const std::vector<TableViolation> violations = CheckFrame(run, frames[k], before, config);
      EXPECT_TRUE(violations.empty()) << what << ": " << violations.front().ToString();
      before = run.table;
    }
    const HashedRun& run = RunOf(*hashed.backend);
    EXPECT_EQ(run.placements[0], key_a.slot0) << hashed.name << ": A did not claim its empty slot0";
    EXPECT_EQ(run.table.counts[key_a.slot0], 1u) << hashed.name;
    EXPECT_EQ(run.table.counts[(key_a.slot0 + 2u) & (config.capacity - 1u)], 1u)
        << hashed.name << ": B's cell was joined";
  }
}

// The animated Cornell box in a table too small for it (256 slots, probes of 8, 6 frames): every frame some records
// find no slot. On every backend, every frame passes the checker from the table before it; priority evicts, its
// tombstones are claimed, and records that failed find room: over frames 1 to 5 fewer records fail than without
// eviction. The contract over the sequence holds for the emulator and Vulkan.
TEST(PriorityEviction, ATableUnderPressureMakesRoomAndKeepsTheContract) {
  constexpr std::uint32_t kFrames = 6;
  PressuredSequence sequence(kFrames);
  auto& [frames, numbers, config] = sequence;
  for (HashedBackend& hashed : HashedBackends()) {
    std::map<std::string, std::uint64_t> failures;  // over frames 1 to 5, by policy
    std::uint64_t evicted = 0, claimed = 0;
    for (const char* policy : {"none", "priority"}) {
      config.eviction = ParseEviction(policy);
      hashed.backend->Reset();
      std::optional<HashTableDump> before;
      for (std::uint32_t k = 0; k < kFrames; ++k) {
        config.frame = k;
        const std::string what = hashed.name + ", " + policy + ", frame " + std::to_string(k);
        hashed.backend->FilterFrame(frames[k], config);
        const HashedRun& run = RunOf(*hashed.backend);
        const std::vector<TableViolation> violations = CheckFrame(run, frames[k], before, config);
        EXPECT_TRUE(violations.empty()) << what << ": " << violations.front().ToString();
        if (k > 0) failures[policy] += run.probe_failures;
        if (config.eviction.by_priority()) {
          evicted += run.evicted;
          for (std::size_t s = 0; before && s < config.capacity; ++s) {
            claimed += before->tags[s] == shared::kTombstoneTag && run.table.counts[s] > 0;
          }
        }
        before = run.table;
      }
    }
    std::printf(
        "%s: records without a slot over frames 1-5: %llu without eviction, %llu with priority; %llu "
        "evicted, %llu tombstones claimed\n",
        hashed.name.c_str(), (unsigned long long)failures["none"], (unsigned long long)failures["priority"],
        (unsigned long long)evicted, (unsigned long long)claimed);
    EXPECT_GT(failures["none"], 0u) << hashed.name << ": no pressure, nothing to evict for";
    EXPECT_LT(failures["priority"], failures["none"]) << hashed.name;
    EXPECT_GT(evicted, 0u) << hashed.name;
    EXPECT_GT(claimed, 0u) << hashed.name;
  }
  config.eviction = ParseEviction("priority");
  EmulatedBackend emulated({}), emulated_rerun({});
  VulkanBackend vulkan(TestDevice(StagingPolicy::kNever)), vulkan_rerun(TestDevice(StagingPolicy::kNever));
  const JudgedBackend judged[] = {{"emulated", &emulated, &emulated_rerun, "rerun", false, false},
                                  {"vulkan", &vulkan, &vulkan_rerun, "rerun", false, true}};
  const CrosscheckReport report = JudgeSequence(frames, numbers, config, judged);
  EXPECT_TRUE(report.Passed()) << report.FirstFailure();
}

// The insertion that claims tombstones under the schedules that interleave it: 3 frames of the animated Cornell box
// in 256 slots with priority eviction, so frame 2's records race for frame 1's tombstones (frame 0 evicts nothing:
// no cell is older than it) and for empty slots, each cell's records looking for it before claiming. Under 20 schedules
// (random and PCT of depth 3, warps of 4) the contract over the sequence holds (every record of a cell in one slot, the
// checker's window invariants).
TEST(PriorityEviction, ClaimingTombstonesHoldsUnderEveryScheduleExplored) {
  const PressuredSequence sequence(3);
  const auto& [frames, numbers, config] = sequence;
  for (int seed = 1; seed <= 10; ++seed) {
    for (const std::string& policy : {"random:" + std::to_string(seed), "pct:" + std::to_string(seed) + ":3"}) {
      EmulatorOptions faithful;
      faithful.mode = simt::Mode::kFaithful;
      faithful.warp_size = 4;
      faithful.schedule = policy;
      EmulatedBackend backend(faithful), rerun(faithful);
      const JudgedBackend judged{"emulated", &backend, &rerun, "rerun", true, false};
      const CrosscheckReport report =
          JudgeSequence(frames, numbers, config, std::span<const JudgedBackend>(&judged, 1));
      EXPECT_TRUE(report.Passed()) << policy << ": " << report.FirstFailure();
    }
  }
}

// The wrong sign over the same pressured sequence, in the emulator and as a user's eviction shader (mapped and
// staged): the contract fails it at level 2 (the built-in eviction passes it over 6 frames of the same sequence in
// ATableUnderPressureMakesRoomAndKeepsTheContract).
TEST(PriorityEviction, TheWrongSignFailsTheContract) {
  const PressuredSequence sequence(3);
  const auto& [frames, numbers, config] = sequence;
  const EvictionKernels wrong_sign(ReclaimKernel, SelectVictimsWrongSign);
  EmulatedBackend emulated({}, AccumulateKernel, wrong_sign), emulated_rerun({}, AccumulateKernel, wrong_sign);
  std::vector<JudgedBackend> broken = {{"emulated", &emulated, &emulated_rerun, "rerun", false, false}};
  std::vector<std::unique_ptr<VulkanBackend>> shaders;
  for (const StagingPolicy staging : kStagingPolicies) {
    for (int i = 0; i < 2; ++i)
      shaders.push_back(std::make_unique<VulkanBackend>(TestDevice(staging), "", kWrongSignShader));
    broken.push_back({std::string("vulkan, staging ") + ToString(staging), shaders[shaders.size() - 2].get(),
                      shaders.back().get(), "rerun", false, true});
  }
  for (const JudgedBackend& judged : broken) {
    const CrosscheckReport report = JudgeSequence(frames, numbers, config, std::span<const JudgedBackend>(&judged, 1));
    EXPECT_FALSE(report.Passed()) << judged.name << ": the wrong sign passed";
    const std::string failure = report.FirstFailure();
    EXPECT_NE(failure.find("eviction differs from the policy"), std::string::npos) << judged.name << ": " << failure;
    std::printf("%s, wrong sign: %s\n", judged.name.c_str(), failure.c_str());
  }
}

}  // namespace
}  // namespace hpsf::testing
