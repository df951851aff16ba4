// The cross-check contract over sequences of frames (verifier/contract/contract_levels.h): every eviction
// policy and temporal mode passes on all three backends frame by frame; the records that a table merged across
// frames (an alias with a cell of an earlier frame, a cell whose records failed to probe in an earlier frame) are
// classified, never blamed on a correct backend; and the broken variants of frames (D7 in the emulator and as a
// shader, D10) fail it.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend.h"
#include "core/eviction.h"
#include "core/temporal.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "property_tests/crosscheck_report_figures.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_backend.h"
#include "tracer/scene_file.h"
#include "verifier/contract/contract_levels.h"
#include "verifier/contract/crosscheck.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

using Key = std::array<std::uint32_t, 6>;

const std::vector<std::string> kAllBackends = {"reference", "emulated", "vulkan"};

// Four frames of the animated Cornell box (camera, light and cube move) pass the contract with every policy (priority
// with 24-bit fingerprints; this table has room, so it evicts nothing: priority_eviction_tests puts it under
// pressure) and mode on every backend, and each level judged something in every frame: records compared with the
// reference, and evictions where the policy evicts.
TEST(CrosscheckFrames, EveryPolicyAndTemporalModePassesOnAllThreeBackends) {
  constexpr std::uint32_t kFrames = 4;
  const std::vector<RecordBatch> frames =
      TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), 24, 2, kFrames);
  Crosschecker checker(kAllBackends);
  struct Case {
    const char* eviction;
    const char* temporal;
    Accumulation accumulation;
    simt::Mode mode;
  };
  std::vector<Case> cases;
  for (const char* eviction : {"none", "strict", "stale:2", "priority"}) {
    for (const char* temporal : {"integrate", "ema:0.5", "adaptive"}) {
      cases.push_back({eviction, temporal, Accumulation::kFixed64, simt::Mode::kFast});
    }
  }
  cases.push_back({"strict", "ema:0.5", Accumulation::kFloat32, simt::Mode::kFaithful});
  cases.push_back({"stale:2", "adaptive", Accumulation::kFloat32, simt::Mode::kFast});
  for (const Case& c : cases) {
    FilterConfig config;
    config.capacity = 1u << 12;
    config.frames = kFrames;
    config.eviction = ParseEviction(c.eviction);
    if (config.eviction.by_priority()) config.fingerprint_bits = 24;
    config.temporal = ParseTemporal(c.temporal);
    config.accumulation = c.accumulation;
    EmulatorOptions emulator;
    emulator.mode = c.mode;
    emulator.warp_size = 8;
    emulator.schedule = "random:5";
    const std::string name = std::string(c.eviction) + ", " + c.temporal + ", " + ToString(c.accumulation) +
                             (c.mode == simt::Mode::kFaithful ? ", faithful" : ", fast");
    const CrosscheckReport report = checker.CheckFrames(frames, config, emulator);
    EXPECT_TRUE(report.Passed()) << name << ": " << report.FirstFailure();
    EXPECT_EQ(report.frames, kFrames);
    for (int level = 1; level <= 4; ++level) EXPECT_TRUE(Level(report, level).applicable) << name << ", " << level;
    EXPECT_NE(Level(report, 1).note.find("accepted records compared over 4 frames"), std::string::npos) << name;
    EXPECT_EQ(Level(report, 3).note.find(" 0 records compared"), std::string::npos) << name << Level(report, 3).note;
    for (const char* backend : {"emulated", "vulkan"}) {
      EXPECT_EQ(QualityOf(report, backend).probe_failures, 0u) << name << ", " << backend;
    }
  }
}

// The records of one frame grouped by full key, each cell's slot0 and fingerprint in `config`'s table; the jitter
// is off, so a record's key is the same in every frame.
struct KeyedCells {
  RecordBatch traced;
  EmulatedRun keyed;
  std::map<Key, std::vector<std::uint32_t>> records_of;

  explicit KeyedCells(const FilterConfig& config) : traced(TracedBatch("cornell", 24, 2)) {
    keyed = EmulatedFilter(traced, config, EmulatorOptions{});
    for (std::uint32_t i = 0; i < keyed.keys.size(); ++i) {
      if (keyed.placements[i] >= config.capacity && keyed.placements[i] != kProbeFailure) continue;  // not keyed
      const shared::KeyWords& w = keyed.keys[i].words;
      records_of[{w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra}].push_back(i);
    }
  }
  const KeyResult& KeyOf(const Key& cell) const { return keyed.keys[records_of.at(cell)[0]]; }
  // Two cells of one slot0 whose fingerprints are equal (same_fingerprint) or differ.
  std::optional<std::pair<Key, Key>> PairSharingSlot0(bool same_fingerprint) const {
    for (auto i = records_of.begin(); i != records_of.end(); ++i) {
      for (auto j = std::next(i); j != records_of.end(); ++j) {
        const KeyResult& a = KeyOf(i->first);
        const KeyResult& b = KeyOf(j->first);
        if (a.slot0 == b.slot0 && (a.fingerprint == b.fingerprint) == same_fingerprint) return {{i->first, j->first}};
      }
    }
    return std::nullopt;
  }
  // A frame that holds only one cell's records: the others keep their pixels but lose their vertex.
  RecordBatch Only(const Key& cell, std::uint32_t frame) const {
    RecordBatch batch = traced;
    batch.frame = frame;
    std::vector<bool> keep(batch.records.size(), false);
    for (const std::uint32_t i : records_of.at(cell)) keep[i] = true;
    for (std::size_t i = 0; i < batch.records.size(); ++i) {
      if (!keep[i]) batch.records[i].path.z &= ~shared::kRecordHasVertex;
    }
    return batch;
  }
};

// The count a hashed backend holds for `cell` after the frames, through the Backend interface.
std::uint64_t CountAfter(Backend& backend, const std::vector<RecordBatch>& frames, FilterConfig config,
                         const KeyedCells& cells, const Key& cell) {
  for (const RecordBatch& frame : frames) {
    config.frame = frame.frame;
    backend.FilterFrame(frame, config);
  }
  return backend.LastHashedRun()->table.counts[backend.LastHashedRun()->placements[cells.records_of.at(cell)[0]]];
}

// Cells A and B share slot0 and fingerprint. Frame 0 holds only A's records, frame 1 only B's: B joins A's slot,
// whose count then holds both cells, while the reference keeps B apart. No single frame sees the alias; the
// contract classifies the slot over the sequence and passes.
TEST(CrosscheckFrames, AnAliasAcrossFramesIsClassifiedNotBlamed) {
  FilterConfig config;
  config.capacity = 64;
  config.probe_limit = 8;
  config.fingerprint_bits = 8;
  config.jitter_scale = 0.0f;
  config.frames = 2;
  const KeyedCells cells(config);
  const auto pair = cells.PairSharingSlot0(true);
  ASSERT_TRUE(pair) << "no two of " << cells.records_of.size() << " cells alias";
  const auto& [a, b] = *pair;
  const std::vector<RecordBatch> frames = {cells.Only(a, 0), cells.Only(b, 1)};
  const std::uint64_t na = cells.records_of.at(a).size(), nb = cells.records_of.at(b).size();

  EmulatedBackend emulated(EmulatorOptions{});
  EXPECT_EQ(CountAfter(emulated, frames, config, cells, b), na + nb) << "B did not join A's slot";
  const CrosscheckReport report = Crosschecker(kAllBackends).CheckFrames(frames, config, EmulatorOptions{});
  EXPECT_TRUE(report.Passed()) << report.FirstFailure();
  for (const char* backend : {"emulated", "vulkan"}) {
    EXPECT_EQ(QualityOf(report, backend).aliased_slots, 1u) << backend;
    EXPECT_EQ(QualityOf(report, backend).aliased_records, nb) << backend << ": B's records, in frame 1";
  }
}

// Cells C and D share slot0, with other fingerprints, in a table of probe limit 1 with strict eviction. Frame 0
// holds D, frame 1 C (its probe fails: D holds the only slot; D is evicted and its slot emptied), frame 2 C again,
// which now claims the slot with frame 2's records alone, while the reference's C holds frames 1 and 2. The
// contract classifies C's slot by its earlier failure and passes.
TEST(CrosscheckFrames, ACellWhoseProbeFailedInAnEarlierFrameIsClassifiedNotBlamed) {
  FilterConfig config;
  config.capacity = 64;
  config.probe_limit = 1;
  config.jitter_scale = 0.0f;
  config.frames = 3;
  config.eviction = ParseEviction("strict");
  const KeyedCells cells(config);
  const auto pair = cells.PairSharingSlot0(false);
  ASSERT_TRUE(pair) << "no two of " << cells.records_of.size() << " cells share slot0";
  const auto& [c, d] = *pair;
  const std::vector<RecordBatch> frames = {cells.Only(d, 0), cells.Only(c, 1), cells.Only(c, 2)};
  const std::uint64_t nc = cells.records_of.at(c).size();

  EmulatedBackend emulated(EmulatorOptions{});
  EXPECT_EQ(CountAfter(emulated, frames, config, cells, c), nc) << "C's slot should hold frame 2 alone";
  ReferenceBackend reference;
  for (const RecordBatch& frame : frames) {
    config.frame = frame.frame;
    reference.FilterFrame(frame, config);
  }
  EXPECT_EQ(reference.result().cells[reference.result().placement[cells.records_of.at(c)[0]]].count, 2 * nc);

  const CrosscheckReport report = Crosschecker(kAllBackends).CheckFrames(frames, config, EmulatorOptions{});
  EXPECT_TRUE(report.Passed()) << report.FirstFailure();
  for (const char* backend : {"emulated", "vulkan"}) {
    EXPECT_EQ(QualityOf(report, backend).probe_failures, nc) << backend << ": C's records, in frame 1";
    EXPECT_EQ(QualityOf(report, backend).aliased_records, nc) << backend << ": C's records, in frame 2";
  }
}

// The broken variants of frames, each a backend pair judged over the animated Cornell box: D7 (a reclaim that
// empties every tombstone) in the emulator and as an eviction shader with strict eviction, and D10 (an accumulate
// that blends while it accumulates) in the emulator and as an accumulate shader (accumulate_D10.spv, reading the
// table before the frame through bindings 9 and 10) with ema:0.5. Each fails the contract; the correct backends
// and the correct user shader beside them pass.
TEST(CrosscheckFrames, BrokenVariantsOfFramesFailTheContract) {
  constexpr std::uint32_t kFrames = 4;
  const std::vector<RecordBatch> frames =
      TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), 24, 2, kFrames);
  std::vector<std::uint32_t> numbers;
  for (const RecordBatch& frame : frames) numbers.push_back(frame.frame);
  FilterConfig config;
  config.capacity = 1024;
  config.frames = kFrames;
  VulkanDevice& device = TestDevice(StagingPolicy::kNever);

  struct Variant {
    std::string name;
    const char* eviction;
    const char* temporal;
    std::unique_ptr<Backend> backend, rerun;
    bool broken;
  };
  auto emulated = [](AccumulateKernelFn kernel, EvictionKernels reclaim) {
    return std::make_unique<EmulatedBackend>(EmulatorOptions{}, kernel, reclaim);
  };
  auto vulkan = [&](const std::string& eviction_spv, const std::string& accumulate_spv = "",
                    const std::string& temporal_spv = "") {
    return std::make_unique<VulkanBackend>(device, accumulate_spv, eviction_spv, temporal_spv);
  };
  const std::string d7_spv = HPSF_SHADER_VARIANT_DIR "/eviction_D7.spv";
  const std::string correct_spv = HPSF_SHADER_VARIANT_DIR "/accumulate_correct.spv";
  const std::string d10_spv = HPSF_SHADER_VARIANT_DIR "/accumulate_D10.spv";
  std::vector<Variant> variants;
  variants.push_back({"emulated", "strict", "integrate", emulated(AccumulateKernel, ReclaimKernel),
                      emulated(AccumulateKernel, ReclaimKernel), false});
  variants.push_back({"emulated D7", "strict", "integrate", emulated(AccumulateKernel, D7ReclaimEveryTombstone),
                      emulated(AccumulateKernel, D7ReclaimEveryTombstone), true});
  variants.push_back({"vulkan", "strict", "integrate", vulkan(""), vulkan(""), false});
  variants.push_back({"vulkan D7", "strict", "integrate", vulkan(d7_spv), vulkan(d7_spv), true});
  variants.push_back({"emulated", "none", "ema:0.5", emulated(AccumulateKernel, ReclaimKernel),
                      emulated(AccumulateKernel, ReclaimKernel), false});
  variants.push_back({"emulated D10", "none", "ema:0.5", emulated(D10BlendDuringAccumulate, ReclaimKernel),
                      emulated(D10BlendDuringAccumulate, ReclaimKernel), true});
  variants.push_back(
      {"vulkan, the correct shader", "none", "ema:0.5", vulkan("", correct_spv), vulkan("", correct_spv), false});
  variants.push_back({"vulkan D10", "none", "ema:0.5", vulkan("", d10_spv), vulkan("", d10_spv), true});
  // A team's own temporal blend (--temporal-spv): the correct one passes, each broken one fails.
  for (const char* temporal : {"correct", "BLEND_UNTOUCHED", "TRUNCATED_BLEND"}) {
    const std::string spv = std::string(HPSF_SHADER_VARIANT_DIR) + "/temporal_" + temporal + ".spv";
    variants.push_back({std::string("vulkan, temporal shader ") + temporal, "none", "ema:0.5", vulkan("", "", spv),
                        vulkan("", "", spv), std::string(temporal) != "correct"});
  }
  for (Variant& v : variants) {
    config.eviction = ParseEviction(v.eviction);
    config.temporal = ParseTemporal(v.temporal);
    const JudgedBackend judged{v.name, v.backend.get(), v.rerun.get(), "rerun", false, v.name.starts_with("vulkan")};
    const CrosscheckReport report = JudgeSequence(frames, numbers, config, std::span<const JudgedBackend>(&judged, 1));
    const std::string name = v.name + ", " + v.eviction + ", " + v.temporal;
    EXPECT_EQ(report.Passed(), !v.broken) << name << ": " << report.FirstFailure();
    if (v.broken) std::printf("%s: %s\n", name.c_str(), report.FirstFailure().c_str());
  }
}

}  // namespace
}  // namespace hpsf::testing
