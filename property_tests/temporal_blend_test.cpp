// Temporal blending (core/temporal.h): a light that moves between two rows of cells shows each mode's
// behaviour against its theory, exactly (no noise: every frame puts the same records in the same cells): the
// EMA's estimate after the move is b + (a - b) alpha^k and its lag (frames to half the step) is the one alpha
// predicts, Schipek's maximum count acts as alpha = M / (M + n), integration converges as K (a - b) / (K + k), and
// the adaptive blend follows the move within a frame where integration takes K. Every backend blends to the
// reference's bits in fixed64 frame by frame, on the light and on the traced animated Cornell box, and the table
// checker passes them; a backend that ignores --temporal is caught by the checker, and one that blends during the
// accumulate (D10) by the checker and the contract. In float32, where each cell takes one add a frame, every
// backend blends to the reference's bits, and each of the checker's float32 blend bounds rejects a planted value.

#include <bit>
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
#include "core/temporal.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "property_tests/grid_batch.h"
#include "property_tests/hashed_backends.h"
#include "property_tests/traced_batch.h"
#include "reference/reference_backend.h"
#include "verifier/checker/table_checker.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kCells = 64;
constexpr std::uint32_t kPerCell = 4;     // records per cell per frame: n
constexpr std::uint32_t kMoveFrame = 12;  // ema:0.9 blends at 0.9 from frame 10 on (its history then exceeds 36)
constexpr std::uint32_t kLightFrames = 26;
constexpr float kLit = 1.0f;
constexpr float kDim = 0.25f;

// The light lights cells 0..31 before kMoveFrame and cells 32..63 from it on; the other row is dim. Cell j is the
// unit cell at x = j, its kPerCell records at its centre, kCells records apart (in different warps, as a frame's
// pixels of one cell are).
RecordBatch LightFrame(std::uint32_t frame) {
  RecordBatch batch;
  batch.width = kCells * kPerCell;
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 1.0;
  for (std::uint32_t r = 0; r < kPerCell; ++r) {
    for (std::uint32_t j = 0; j < kCells; ++j) {
      const bool lit = (j < kCells / 2) == (frame < kMoveFrame);
      VertexSample v;
      v.pixel = r * kCells + j;
      v.position = glm::vec3(float(j) + 0.5f, 0.5f, 0.5f);
      v.previous = v.position + glm::vec3(0.0f, 0.0f, -1.0f);
      v.contribution = glm::vec3(lit ? kLit : kDim);
      v.throughput = glm::vec3(1.0f);
      batch.records.push_back(MakeVertexRecord(v));
    }
  }
  return batch;
}

FilterConfig LightConfig(const std::string& temporal) {
  FilterConfig config = GridConfig(256, 16);
  config.frames = kLightFrames;
  config.temporal = ParseTemporal(temporal);
  return config;
}

// Per frame, the red average of cell 0 (lit, then dim) in the reference's table.
std::vector<double> CellZeroAverages(const std::string& temporal) {
  const FilterConfig base = LightConfig(temporal);
  ReferenceBackend reference;
  std::vector<double> averages;
  for (std::uint32_t k = 0; k < kLightFrames; ++k) {
    FilterConfig config = base;
    config.frame = k;
    reference.FilterFrame(LightFrame(k), config);
    const FilterResult& result = reference.result();
    const TableCell& cell = result.cells[result.placement[0]];
    averages.push_back(std::ldexp(double(cell.fixed_sum[0]), -result.stats.fixed_point_bits) / double(cell.count));
  }
  return averages;
}

// Frames after the move (the move's frame is 1) until the estimate has covered half the step.
int FramesToHalf(const std::vector<double>& averages) {
  for (std::uint32_t k = kMoveFrame; k < averages.size(); ++k) {
    if (averages[k] - kDim <= 0.5 * (kLit - kDim)) return int(k - kMoveFrame + 1);
  }
  return -1;
}

TEST(Temporal, ParsesItsModesAndNamesABadOne) {
  EXPECT_EQ(ParseTemporal("integrate"), Temporal{});
  EXPECT_EQ(ParseTemporal("ema:0.9"), (Temporal{TemporalMode::kEma, 0.9, 0}));
  EXPECT_EQ(ParseTemporal("ema:1:64"), (Temporal{TemporalMode::kEma, 1.0, 64}));
  EXPECT_EQ(ParseTemporal("adaptive"), (Temporal{TemporalMode::kAdaptive, 1.0, 0}));
  EXPECT_EQ(ParseTemporal("ema:0.9:64").ToString(), "ema:0.9:64");
  for (const char* bad : {"ema", "ema:", "ema:0", "ema:1.5", "ema:-0.5", "ema:0.9:0", "ema:0.9:", "ema:0.9x",
                          "ema:0.9:4:2", "ema:nan", "integrate:2", "adaptive:1", ""}) {
    try {
      ParseTemporal(bad);
      ADD_FAILURE() << bad << " parsed";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--temporal: ", 0), 0u) << e.what();
    }
  }
}

// With an alpha the history never exceeds, the blend is integration and keeps the exact sums; a capped history or
// a smaller alpha blends, to a count whose integration weight is at least alpha, and no more than the integrated
// sum plus one average (so F holds).
TEST(Temporal, TheBlendIsIntegrationUnlessCappedAndStaysWithinTheIntegratedSum) {
  const CellState before{{400, 800, 0}, {}, 4};
  const CellState accumulated{{400 + 100, 800 + 300, 0}, {}, 4 + 2};
  EXPECT_EQ(BlendCellState(MakeTemporalParams(ParseTemporal("integrate"), Accumulation::kFixed64, 0, 0),
                           Accumulation::kFixed64, before, accumulated)
                .fixed_sum,
            accumulated.fixed_sum);
  EXPECT_EQ(BlendCellState(MakeTemporalParams(ParseTemporal("ema:0.9"), Accumulation::kFixed64, 0, 0),
                           Accumulation::kFixed64, before, accumulated)
                .count,
            6u);
  for (const char* mode : {"ema:0.5", "ema:0.25", "ema:1:2", "adaptive"}) {
    const shared::TemporalParams params = MakeTemporalParams(ParseTemporal(mode), Accumulation::kFixed64, 0, 0);
    const CellState blended = BlendCellState(params, Accumulation::kFixed64, before, accumulated);
    EXPECT_LT(blended.count, 6u) << mode;
    EXPECT_GE(blended.count, 2u) << mode;
    for (int c = 0; c < 3; ++c) {
      EXPECT_LE(blended.fixed_sum[c], accumulated.fixed_sum[c] + accumulated.fixed_sum[c] / 6 + 1) << mode;
      const double average = double(blended.fixed_sum[c]) / double(blended.count);
      const double history = double(before.fixed_sum[c]) / 4.0;
      const double frame = double(accumulated.fixed_sum[c] - before.fixed_sum[c]) / 2.0;
      EXPECT_GE(average, std::min(history, frame) - 1.0) << mode << ", channel " << c;
      EXPECT_LE(average, std::max(history, frame) + 1.0) << mode << ", channel " << c;
    }
  }
}

// The EMA after the move: b + (a - b) alpha^k, k frames after it, to rounding; the lag to half the step is the
// smallest k with alpha^k <= 1/2. ema:ALPHA integrates while the history is young, then blends at ALPHA (the
// light has been still for kMoveFrame frames); ema:1:M is Schipek's maximum count, alpha = M / (M + n).
TEST(Temporal, TheEmasLagAfterAMovingLightIsTheOneItsAlphaPredicts) {
  const std::map<std::string, double> alpha_of = {
      {"ema:0.5", 0.5}, {"ema:0.75", 0.75}, {"ema:0.9", 0.9}, {"ema:1:16", 16.0 / (16.0 + kPerCell)}};
  for (const auto& [mode, alpha] : alpha_of) {
    const std::vector<double> averages = CellZeroAverages(mode);
    EXPECT_EQ(averages[kMoveFrame - 1], kLit) << mode;
    for (std::uint32_t k = kMoveFrame; k < kLightFrames; ++k) {
      const double predicted = kDim + (kLit - kDim) * std::pow(alpha, double(k - kMoveFrame + 1));
      EXPECT_NEAR(averages[k], predicted, 1e-12) << mode << ", frame " << k;
    }
    const int predicted_lag = int(std::ceil(std::log(0.5) / std::log(alpha) - 1e-12));
    EXPECT_EQ(FramesToHalf(averages), predicted_lag) << mode;
    std::printf("%s: alpha %.3f, frames to half the step %d (predicted %d)\n", mode.c_str(), alpha,
                FramesToHalf(averages), predicted_lag);
  }
}

// Integration after the move: (K a + k b) / (K + k) with K = kMoveFrame still frames, to rounding: the error
// falls as K (a - b) / (K + k), to half the step after K frames. The adaptive blend integrates while the light is
// still (the same bits as integration) and after the move weighs the history by the integration's alpha times
// 1 - |f - h| / (f + h): it covers half the step in one frame.
TEST(Temporal, IntegrationConvergesAsTheoryPredictsAndTheAdaptiveBlendFollowsTheMove) {
  const std::vector<double> integrated = CellZeroAverages("integrate");
  for (std::uint32_t k = kMoveFrame; k < kLightFrames; ++k) {
    const double after = double(k - kMoveFrame + 1);
    const double predicted = (kMoveFrame * double(kLit) + after * kDim) / (kMoveFrame + after);
    EXPECT_NEAR(integrated[k], predicted, 1e-12) << "frame " << k;
  }
  EXPECT_EQ(FramesToHalf(integrated), int(kMoveFrame));
  const std::vector<double> adaptive = CellZeroAverages("adaptive");
  for (std::uint32_t k = 0; k < kMoveFrame; ++k) EXPECT_EQ(adaptive[k], integrated[k]) << "frame " << k;
  const double change = (kLit - kDim) / double(kLit + kDim);
  const double w = kMoveFrame * kPerCell, alpha = w / (w + kPerCell) * (1.0 - change);
  EXPECT_NEAR(adaptive[kMoveFrame], alpha * kLit + (1.0 - alpha) * kDim, 1e-12);
  EXPECT_EQ(FramesToHalf(adaptive), 1);
  std::printf("frames to half the step: integrate %d, adaptive %d\n", FramesToHalf(integrated), FramesToHalf(adaptive));
}

// Reference and hashed backends side by side over a sequence; each hashed frame judged by the checker from the
// table before it, its image and every placed record's cell (sums and count) compared with the reference's bit
// for bit. Returns the slots blended over the sequence (count changed otherwise than by integration).
std::uint64_t CompareWithTheReference(Backend& hashed, const std::string& name, const std::vector<RecordBatch>& frames,
                                      FilterConfig config) {
  ReferenceBackend reference;
  std::optional<HashTableDump> before;
  std::uint64_t blended = 0;
  for (std::uint32_t k = 0; k < frames.size(); ++k) {
    config.frame = k;
    const std::string what = name + ", " + config.temporal.ToString() + ", frame " + std::to_string(k);
    const Image& expected = reference.FilterFrame(frames[k], config);
    const Image& image = hashed.FilterFrame(frames[k], config);
    const HashedRun& run = RunOf(hashed);
    const std::vector<TableViolation> violations =
        CheckTable({run.table, frames[k].records, run.keys, run.placements, before ? &*before : nullptr,
                    config.eviction, k, config.temporal});
    EXPECT_TRUE(violations.empty()) << what << ": " << violations.front().ToString();
    EXPECT_EQ(run.probe_failures, 0u) << what;
    if (config.accumulation == Accumulation::kFixed64) {
      EXPECT_TRUE(image.pixels == expected.pixels) << what << ": image differs from the reference's";
      const FilterResult& cells = reference.result();
      int mismatches = 0;
      for (std::size_t i = 0; i < run.placements.size() && mismatches < 3; ++i) {
        const std::uint32_t slot = run.placements[i];
        if (slot >= config.capacity) continue;
        const TableCell& cell = cells.cells[cells.placement[i]];
        if (run.table.fixed_sums[slot] != cell.fixed_sum || run.table.counts[slot] != cell.count) {
          ADD_FAILURE() << what << ": record " << i << "'s slot " << slot << " differs from its reference cell";
          ++mismatches;
        }
      }
    }
    if (before) {
      std::vector<std::uint64_t> placed(config.capacity, 0);
      for (std::uint32_t slot : run.placements) {
        if (slot < config.capacity) ++placed[slot];
      }
      for (std::size_t s = 0; s < config.capacity; ++s) {
        blended += before->counts[s] > 0 && placed[s] > 0 && run.table.counts[s] != before->counts[s] + placed[s];
      }
    }
    before = run.table;
  }
  return blended;
}

TEST(Temporal, EveryBackendBlendsTheMovingLightToTheReferencesBits) {
  std::vector<RecordBatch> frames;
  for (std::uint32_t k = 0; k < kLightFrames; ++k) frames.push_back(LightFrame(k));
  for (const char* mode : {"ema:0.75", "ema:1:16", "adaptive"}) {
    for (HashedBackend& hashed : HashedBackends()) {
      const std::uint64_t blended = CompareWithTheReference(*hashed.backend, hashed.name, frames, LightConfig(mode));
      EXPECT_GT(blended, 0u) << hashed.name << ", " << mode << ": the oracle was never fed a blend";
    }
  }
}

// The animated Cornell box (camera, light and cube move), with jitter: cells of every count, blended in fixed64
// to the reference's bits on every backend, with and without eviction; in float32 the checker's bounds hold.
TEST(Temporal, EveryBackendBlendsTheAnimatedCornellBoxAsTheReferenceDoes) {
  constexpr std::uint32_t kFrames = 4;
  const std::vector<RecordBatch> frames =
      TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), 24, 2, kFrames);
  struct Case {
    const char* temporal;
    const char* eviction;
    Accumulation accumulation;
  };
  const Case cases[] = {{"ema:0.6", "none", Accumulation::kFixed64},
                        {"ema:1:3", "strict", Accumulation::kFixed64},
                        {"adaptive", "stale:2", Accumulation::kFixed64},
                        {"ema:0.6", "none", Accumulation::kFloat32},
                        {"adaptive", "none", Accumulation::kFloat32}};
  for (const Case& c : cases) {
    FilterConfig config;
    config.capacity = 1u << 12;
    config.frames = kFrames;
    config.temporal = ParseTemporal(c.temporal);
    config.eviction = ParseEviction(c.eviction);
    config.accumulation = c.accumulation;
    for (HashedBackend& hashed : HashedBackends()) {
      const std::string name = hashed.name + ", " + c.eviction + ", " + ToString(c.accumulation);
      EXPECT_GT(CompareWithTheReference(*hashed.backend, name, frames, config), 10u) << name << ", " << c.temporal;
    }
  }
}

// One record per cell a frame, so that no order of adds can differ between backends, its contribution inexact
// in float and 5.3 times larger every other frame: (history + v) - history, taken in float where v is more than
// the history (no longer exact by Sterbenz's lemma), is not v, nor what double arithmetic gives.
RecordBatch OneAddPerCellFrame(std::uint32_t frame) {
  RecordBatch batch;
  batch.width = kCells;
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 1.0;
  for (std::uint32_t j = 0; j < kCells; ++j) {
    VertexSample v;
    v.pixel = j;
    v.position = glm::vec3(float(j) + 0.5f, 0.5f, 0.5f);
    v.previous = v.position + glm::vec3(0.0f, 0.0f, -1.0f);
    const float value = 0.1f * float(1 + j % 7) * (frame % 2 ? 5.3f : 1.0f) + 0.013f * float(frame);
    v.contribution = glm::vec3(value, value * 3.0f, value / 7.0f);
    v.throughput = glm::vec3(1.0f);
    batch.records.push_back(MakeVertexRecord(v));
  }
  return batch;
}

// float32 blends on every hashed backend to the reference's bits where each cell takes one add a frame: the
// blend (shared::BlendCell over the table's float sums) is then the same arithmetic everywhere, so a backend that
// computed its frame's sum otherwise (in double from the records, say) differs here while staying inside the
// checker's float32 bounds. Frames 1.. blend; every blended cell is compared.
TEST(Temporal, Float32BlendsAreTheReferencesBitsWhereEachCellTakesOneAdd) {
  constexpr std::uint32_t kFrames = 8;
  for (const char* mode : {"ema:0.75", "ema:1:3", "adaptive"}) {
    for (HashedBackend& hashed : HashedBackends()) {
      FilterConfig config = GridConfig(256, 16);
      config.frames = kFrames;
      config.temporal = ParseTemporal(mode);
      config.accumulation = Accumulation::kFloat32;
      ReferenceBackend reference;
      std::uint64_t compared = 0;
      for (std::uint32_t k = 0; k < kFrames; ++k) {
        config.frame = k;
        const RecordBatch batch = OneAddPerCellFrame(k);
        reference.FilterFrame(batch, config);
        hashed.backend->FilterFrame(batch, config);
        const HashedRun& run = RunOf(*hashed.backend);
        const FilterResult& cells = reference.result();
        for (std::size_t i = 0; i < batch.records.size(); ++i) {
          const std::uint32_t slot = run.placements[i];
          ASSERT_LT(slot, config.capacity);
          const TableCell& cell = cells.cells[cells.placement[i]];
          EXPECT_EQ(run.table.counts[slot], cell.count)
              << hashed.name << ", " << mode << ", frame " << k << ", cell " << i;
          for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(std::bit_cast<std::uint32_t>(run.table.float_sums[slot][c]),
                      std::bit_cast<std::uint32_t>(cell.float_sum[c]))
                << hashed.name << ", " << mode << ", frame " << k << ", cell " << i << ", channel " << c << ": "
                << run.table.float_sums[slot][c] << " against the reference's " << cell.float_sum[c];
          }
          compared += k > 0;
        }
      }
      EXPECT_EQ(compared, std::uint64_t(kCells) * (kFrames - 1)) << "the oracle was fed every blend";
    }
  }
}

// The checker's float32 blend bounds, each made to fire by a value planted into a correct table: a blended
// average must lie between the history's and the frame's (widened by a few ulps for the float adds), so one
// 1e-5 beyond either end is named and one 1e-5 inside is not; ema's count is exact, adaptive's at most
// min(history, max count) + n. Frame 1 of OneAddPerCellFrame on the emulator, cell 5 (history 0.6, frame 3.19).
TEST(Temporal, TheCheckersFloat32BlendBoundsRejectAPlantedValueJustOutside) {
  for (const char* mode : {"ema:0.75", "adaptive"}) {
    FilterConfig config = GridConfig(256, 16);
    config.frames = 2;
    config.temporal = ParseTemporal(mode);
    config.accumulation = Accumulation::kFloat32;
    EmulatedBackend emulated{EmulatorOptions{}};
    const RecordBatch first = OneAddPerCellFrame(0), second = OneAddPerCellFrame(1);
    emulated.FilterFrame(first, config);
    const HashTableDump before = emulated.run().table;
    config.frame = 1;
    emulated.FilterFrame(second, config);
    const EmulatedRun& run = emulated.run();
    constexpr std::uint32_t kRecord = 5;
    const std::uint32_t slot = run.placements[kRecord];
    auto blend_violations = [&](const HashTableDump& table) {
      int found = 0;
      for (const TableViolation& v :
           CheckTable({table, second.records, run.keys, run.placements, &before, {}, 1, config.temporal})) {
        found += v.invariant == TableInvariant::kTemporalBlend && v.slot == slot;
      }
      return found;
    };
    ASSERT_EQ(blend_violations(run.table), 0) << mode << ": the correct table";
    const double history = double(before.float_sums[slot][0]) / double(before.counts[slot]);
    const double frame = double(second.records[kRecord].contribution[0]);
    ASSERT_GT(frame, 2.0 * history);
    const double count = double(run.table.counts[slot]);
    const struct {
      double average;
      int violations;
      const char* what;
    } plants[] = {{frame * (1.0 + 1e-5), 1, "above the frame's average"},
                  {frame * (1.0 - 1e-5), 0, "just below the frame's average"},
                  {history * (1.0 - 1e-5), 1, "below the history's average"},
                  {history * (1.0 + 1e-5), 0, "just above the history's average"}};
    for (const auto& plant : plants) {
      HashTableDump planted = run.table;
      planted.float_sums[slot][0] = float(plant.average * count);
      EXPECT_EQ(blend_violations(planted), plant.violations) << mode << ": an average " << plant.what;
    }
    HashTableDump recounted = run.table;
    recounted.counts[slot] = config.temporal.mode == TemporalMode::kEma ? run.table.counts[slot] + 1
                                                                        : before.counts[slot] + 1 + 1;  // most + 1
    EXPECT_EQ(blend_violations(recounted), 1) << mode << ": a count past its bound";
  }
}

// A backend that ignores --temporal and integrates: every slot it should have blended is named by the checker.
TEST(Temporal, TheCheckerCatchesABackendThatIgnoresTheTemporalMode) {
  FilterConfig config = LightConfig("integrate");
  EmulatedBackend emulated{EmulatorOptions{}};
  std::optional<HashTableDump> before;
  std::map<TableInvariant, int> violations;
  for (std::uint32_t k = 0; k < kLightFrames; ++k) {
    config.frame = k;
    const RecordBatch batch = LightFrame(k);
    emulated.FilterFrame(batch, config);
    const EmulatedRun& run = emulated.run();
    for (const TableViolation& v : CheckTable({run.table,
                                               batch.records,
                                               run.keys,
                                               run.placements,
                                               before ? &*before : nullptr,
                                               {},
                                               k,
                                               ParseTemporal("ema:0.75")})) {
      ++violations[v.invariant];
    }
    before = run.table;
  }
  // Every cell blends from frame 4 on (the history's weight then exceeds 0.75).
  EXPECT_EQ(violations[TableInvariant::kTemporalBlend], int(kCells * (kLightFrames - 4)));
}

// D10: the emulator's accumulate that blends each slot right after a record's add, reading the table it is still
// accumulating. Fast (all cores, atomics as they come) and faithful (warps of 8, a random schedule): the checker
// names blended slots and the image differs from the reference's.
TEST(Temporal, D10ABlendDuringTheAccumulateIsCaughtByTheCheckerAndTheContract) {
  EmulatorOptions faithful;
  faithful.mode = simt::Mode::kFaithful;
  faithful.warp_size = 8;
  faithful.schedule = "random:7";
  for (const EmulatorOptions& options : {EmulatorOptions{}, faithful}) {
    const std::string name = options.mode == simt::Mode::kFast ? "emulated fast" : "emulated faithful";
    FilterConfig config = LightConfig("ema:0.75");
    EmulatedBackend d10(options, D10BlendDuringAccumulate);
    ReferenceBackend reference;
    std::optional<HashTableDump> before;
    int blend_violations = 0, images_differ = 0;
    for (std::uint32_t k = 0; k < kLightFrames; ++k) {
      config.frame = k;
      const RecordBatch batch = LightFrame(k);
      images_differ += d10.FilterFrame(batch, config).pixels != reference.FilterFrame(batch, config).pixels;
      const EmulatedRun& run = d10.run();
      for (const TableViolation& v : CheckTable({run.table,
                                                 batch.records,
                                                 run.keys,
                                                 run.placements,
                                                 before ? &*before : nullptr,
                                                 {},
                                                 k,
                                                 config.temporal})) {
        blend_violations += v.invariant == TableInvariant::kTemporalBlend;
      }
      before = run.table;
    }
    EXPECT_GT(blend_violations, 0) << name << ": the checker misses D10";
    EXPECT_GT(images_differ, 0) << name << ": the contract misses D10";
    std::printf("%s, D10: %d blended slots named, %d of %u frames' images differ\n", name.c_str(), blend_violations,
                images_differ, kLightFrames);
  }
}

}  // namespace
}  // namespace hpsf::testing
