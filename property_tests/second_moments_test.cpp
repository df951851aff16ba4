// Per-cell second moments (--second-moments, core/shared/second_moment.h, core/cell_moments.h), label `adaptive`:
// - the variance a cell reports is its samples' variance within the stated bound, for cells built from known
//   distributions, on every backend, in fixed64 and float32; and the sample variance of the uniform distribution is
//   its theoretical 1/3 within five standard errors;
// - a bright, nearly constant cell (mean 1000, spread 0.01) is resolved in fixed64, where the same difference of
//   means taken in float32 (the broken variant: a variance from float sums) cancels to nonsense;
// - on the Cornell box every cell's variance is its records' within the bound, on every backend;
// - over 16 replicate runs of the furnace and the Cornell box, a cell's variance predicts the spread of its mean
//   across the runs;
// - the squares hold the cross-check contract on all three backends over sequences, under every temporal mode and
//   eviction policy, with several levels and compaction.

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend.h"
#include "core/cell_moments.h"
#include "core/hashed_run.h"
#include "core/shared/rng.h"
#include "core/shared/second_moment.h"
#include "emulated/emulated_backend.h"
#include "property_tests/grid_batch.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_filter.h"
#include "tracer/scene_file.h"
#include "verifier/contract/crosscheck.h"
#include "verifier/metrics/cell_variance.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kSamples = 4096;

// Grey samples v_i in one unit cell, all at its centre: the cell's channel mean is v.
RecordBatch OneCellBatch(const std::vector<float>& values) {
  RecordBatch batch;
  batch.width = std::uint32_t(values.size());
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 1.0;
  for (std::uint32_t j = 0; j < values.size(); ++j) {
    VertexSample v;
    v.pixel = j;
    v.position = glm::vec3(0.5f);
    v.previous = v.position + glm::vec3(0.0f, 0.0f, -1.0f);
    v.contribution = glm::vec3(values[j]);
    v.throughput = glm::vec3(1.0f);
    batch.records.push_back(MakeVertexRecord(v));
  }
  return batch;
}

// The samples' own variance of the channel mean m = y / 3 (two passes, in long double): what the cell should report.
double ExactVariance(const std::vector<glm::vec3>& contributions) {
  long double mean = 0.0L;
  for (const glm::vec3& c : contributions) mean += shared::Brightness(c) / 3.0L;
  mean /= contributions.size();
  long double squares = 0.0L;
  for (const glm::vec3& c : contributions) {
    const long double d = shared::Brightness(c) / 3.0L - mean;
    squares += d * d;
  }
  return double(squares / contributions.size());
}
double ExactVariance(const std::vector<float>& grey) {
  std::vector<glm::vec3> contributions;
  for (const float v : grey) contributions.emplace_back(v);
  return ExactVariance(contributions);
}

// Counter-RNG uniforms in [0, 1), by seed.
std::vector<float> Uniforms(std::uint32_t seed, float low, float width) {
  std::vector<float> values(kSamples);
  for (std::uint32_t i = 0; i < kSamples; ++i) values[i] = low + width * shared::RandomFloat({seed, 0u, i, 0u, 0u}, 0u);
  return values;
}

FilterConfig OneCellConfig(Accumulation accumulation) {
  FilterConfig config = GridConfig(64, 16);
  config.accumulation = accumulation;
  config.second_moments = true;
  return config;
}

// The moments of the one cell each backend's table holds.
struct BackendMoments {
  std::string backend;
  CellMoments moments;
};

std::vector<BackendMoments> MomentsOnEveryBackend(const std::vector<float>& values, Accumulation accumulation) {
  const RecordBatch batch = OneCellBatch(values);
  const FilterConfig config = OneCellConfig(accumulation);
  std::vector<BackendMoments> out;
  const FilterResult reference = ReferenceFilter(batch, config);
  EXPECT_EQ(reference.cells.size(), 1u);
  out.push_back({"reference", MomentsOfCell(reference.cells.at(0), accumulation, reference.stats)});
  EmulatedBackend emulated(EmulatorOptions{});
  VulkanBackend vulkan(TestDevice(StagingPolicy::kAuto));
  for (Backend* backend : std::initializer_list<Backend*>{&emulated, &vulkan}) {
    backend->Reset();
    backend->FilterFrame(batch, config);
    const HashedRun& run = *backend->LastHashedRun();
    out.push_back({backend->Name(), MomentsOfSlot(run.table, run.placements.at(0))});
  }
  return out;
}

// The variance of U(0, 2) is 1/3; the sample variance of n draws has standard error sqrt((mu4 - sigma^4) / n), with
// the fourth central moment mu4 = 2^4 / 80: about 0.0047 at n = 4096. Five standard errors: a false alarm below one
// in a million (the sample variance is close to normal at this n), and a variance off by 7% is caught.
TEST(SecondMoments, TheVarianceOfAUniformCellIsItsSamplesAndItsTheorys) {
  const std::vector<float> values = Uniforms(11, 0.0f, 2.0f);
  const double exact = ExactVariance(values);
  const double standard_error = std::sqrt((16.0 / 80.0 - 1.0 / 9.0) / kSamples);
  EXPECT_NEAR(exact, 1.0 / 3.0, 5.0 * standard_error);
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    for (const BackendMoments& b : MomentsOnEveryBackend(values, accumulation)) {
      const std::string where = b.backend + ", " + ToString(accumulation);
      EXPECT_LE(std::abs(b.moments.variance - exact), b.moments.variance_bound) << where;
      EXPECT_TRUE(b.moments.Resolved()) << where;
      EXPECT_NEAR(b.moments.variance, 1.0 / 3.0, 5.0 * standard_error) << where;
    }
  }
}

// Mean 1000, spread U(-0.01, 0.01): a variance of 3.3e-5 beside a squared mean of 1e6. fixed64's exact sums resolve
// it to its bound (a relative error below 1e-3); a float32 table's bound is larger than the variance itself, so it
// reports it unresolved rather than as a number.
TEST(SecondMoments, ABrightNearlyConstantCellIsResolvedInFixed64) {
  const std::vector<float> values = Uniforms(12, 999.99f, 0.02f);
  const double exact = ExactVariance(values);
  for (const BackendMoments& b : MomentsOnEveryBackend(values, Accumulation::kFixed64)) {
    EXPECT_LE(std::abs(b.moments.variance - exact), b.moments.variance_bound) << b.backend;
    EXPECT_LT(b.moments.variance_bound, 1e-3 * exact) << b.backend;
  }
  for (const BackendMoments& b : MomentsOnEveryBackend(values, Accumulation::kFloat32)) {
    EXPECT_LE(std::abs(b.moments.variance - exact), b.moments.variance_bound) << b.backend << ", float32";
    EXPECT_FALSE(b.moments.Resolved()) << b.backend << ", float32";
  }
}

// The broken variant: the same means, the difference taken in float32 as a shader might, cancels catastrophically:
// the bound that holds fixed64's double readout is broken by orders of magnitude.
TEST(SecondMoments, AVarianceFromFloatMeansCancelsAndIsCaught) {
  const std::vector<float> values = Uniforms(12, 999.99f, 0.02f);
  const double exact = ExactVariance(values);
  const CellMoments right = MomentsOnEveryBackend(values, Accumulation::kFixed64).at(0).moments;
  const float mean = float(right.mean_brightness), square = float(right.mean_square);
  const float cancelled = (square - mean * mean) / 9.0f;
  EXPECT_LE(std::abs(right.variance - exact), right.variance_bound);
  EXPECT_GT(std::abs(double(cancelled) - exact), 100.0 * right.variance_bound)
      << "float " << cancelled << ", exact " << exact;
}

// On the Cornell box (fireflies and all), every cell's variance is within its bound of the two-pass variance of the
// records the reference placed there, on the reference and (where the slot holds the same records: nothing aliased or
// failed in this roomy table) on the emulator and Vulkan, in fixed64 and float32.
TEST(SecondMoments, EveryCellOfASceneHoldsItsRecordsVariance) {
  const RecordBatch batch = TracedBatch(HPSF_SCENES_DIR "/cornell.json", 48, 4);
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    FilterConfig config;
    config.capacity = 1u << 14;
    config.accumulation = accumulation;
    config.second_moments = true;
    const FilterResult reference = ReferenceFilter(batch, config);
    std::vector<std::vector<std::size_t>> records(reference.cells.size());
    for (std::size_t i = 0; i < batch.records.size(); ++i) {
      const std::uint32_t cell = reference.placement[i];
      if (cell == kNoCell) continue;
      records[cell].push_back(i);
    }
    EmulatedBackend emulated(EmulatorOptions{});
    VulkanBackend vulkan(TestDevice(StagingPolicy::kAuto));
    emulated.FilterFrame(batch, config);
    vulkan.FilterFrame(batch, config);
    std::size_t judged = 0;
    for (std::size_t c = 0; c < reference.cells.size(); ++c) {
      if (records[c].size() < 2) continue;
      std::vector<glm::vec3> contributions;
      for (const std::size_t i : records[c]) contributions.emplace_back(batch.records[i].contribution);
      const double exact = ExactVariance(contributions);
      const CellMoments own = MomentsOfCell(reference.cells[c], accumulation, reference.stats);
      EXPECT_LE(std::abs(own.variance - exact), own.variance_bound) << "reference cell " << c;
      for (const Backend* backend : std::initializer_list<const Backend*>{&emulated, &vulkan}) {
        const HashedRun& run = *backend->LastHashedRun();
        const HashTableDump& t = run.table;
        const std::uint32_t slot = run.placements[records[c].front()];
        ASSERT_LT(slot, t.capacity);
        ASSERT_EQ(t.counts[slot], records[c].size()) << backend->Name() << ": the roomy table aliased a cell";
        const CellMoments m = MomentsOfSlot(t, slot);
        EXPECT_LE(std::abs(m.variance - exact), m.variance_bound) << backend->Name() << ", cell " << c;
      }
      ++judged;
    }
    EXPECT_GT(judged, 500u) << ToString(accumulation);
  }
}

// Against replicate runs: 16 seeds of a scene at 32 x 32 x 4 spp, jitter off so that a cell is the same region in every
// run. For each cell reached in every run with at least 2 samples, the variance of its channel mean across the runs
// is compared with what its own second moments predict, the mean over runs of variance / (n - 1) (the cell reports the
// samples' variance over n; over n - 1 it is the unbiased estimate of its mean's variance). Pooled over the cells, the
// mean of the per-cell ratios must be 1 within 4 standard errors of that mean (the cells are independent; each
// ratio's spread is measured, not assumed). The furnace's light is the same everywhere, so a cell's samples are
// independent draws of one distribution; the Cornell box's varies across a cell and its samples are stratified by
// pixel, which would make the mean spread less than predicted if a cell's light varied much across it. The
// alternative the test rejects: a variance off by a constant factor, such as N53's, the brightness's variance (9
// times the channel mean's), which the test shows failing.
TEST(SecondMoments, ACellsVarianceMatchesItsMeansSpreadOverReplicateRuns) {
  constexpr std::uint32_t kRuns = 16;
  for (const char* scene : {"furnace", "cornell"}) {
    FilterConfig config;
    config.second_moments = true;
    config.jitter_scale = 0.0f;
    struct Cell {
      std::vector<double> means, predicted;  // per run: the channel mean, and its variance predicted
    };
    std::map<std::array<std::uint32_t, 6>, Cell> cells;
    for (std::uint32_t seed = 1; seed <= kRuns; ++seed) {
      TraceOptions trace;
      trace.width = trace.height = 32;
      trace.samples_per_pixel = 4;
      trace.seed = seed;
      config.seed = seed;
      const FilterResult run = ReferenceFilter(TraceRecords(LoadScene(scene), trace).batch, config);
      for (const TableCell& c : run.cells) {
        if (c.count < 2) continue;
        const CellMoments m = MomentsOfCell(c, Accumulation::kFixed64, run.stats);
        Cell& cell = cells[c.key];
        cell.means.push_back(m.mean_brightness / 3.0);
        cell.predicted.push_back(m.variance / double(c.count - 1));
      }
    }
    const auto pooled = [&](double factor) {
      std::vector<double> ratios;
      for (const auto& [key, cell] : cells) {
        if (cell.means.size() != kRuns) continue;
        double mean = 0.0, spread = 0.0, predicted = 0.0;
        for (double m : cell.means) mean += m / kRuns;
        for (double m : cell.means) spread += (m - mean) * (m - mean) / (kRuns - 1);
        for (double v : cell.predicted) predicted += factor * v / kRuns;
        if (predicted > 0.0) ratios.push_back(spread / predicted);
      }
      double mean = 0.0, variance = 0.0;
      for (double r : ratios) mean += r / double(ratios.size());
      for (double r : ratios) variance += (r - mean) * (r - mean) / double(ratios.size() - 1);
      return std::array<double, 3>{mean, std::sqrt(variance / double(ratios.size())), double(ratios.size())};
    };
    const auto [ratio, error, judged] = pooled(1.0);
    std::printf("%s: %g cells in all %u runs: spread over predicted %.4f, standard error %.4f\n", scene, judged, kRuns,
                ratio, error);
    EXPECT_GT(judged, 100.0) << scene;
    EXPECT_LT(std::abs(ratio - 1.0), 4.0 * error) << scene;
    const auto [wrong, wrong_error, unused] = pooled(9.0);  // the brightness's variance taken for the channel mean's
    std::printf("%s, with the brightness's variance: %.4f, standard error %.4f\n", scene, wrong, wrong_error);
    EXPECT_GT(std::abs(wrong - 1.0), 4.0 * wrong_error) << scene;
  }
}

// Three frames of the Cornell box through one table per backend: the checker holds every slot's square sum (exactly
// in fixed64) and level 3 compares it with the reference's, under each temporal mode, with and without eviction,
// and with two levels and the occupied list.
TEST(SecondMoments, HoldTheContractOnAllThreeBackendsOverFrames) {
  const std::vector<RecordBatch> frames = TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell.json"), 24, 2, 3);
  Crosschecker checker({"reference", "emulated", "vulkan"});
  struct Case {
    const char* temporal;
    const char* eviction;
    Accumulation accumulation;
    std::uint32_t levels;
    bool compacting;
  };
  const Case cases[] = {
      {"integrate", "none", Accumulation::kFixed64, 1, false},
      {"ema:0.5", "strict", Accumulation::kFixed64, 1, false},
      {"adaptive", "stale:2", Accumulation::kFixed64, 1, false},
      {"ema:0.5:8", "priority", Accumulation::kFixed64, 2, true},
      {"integrate", "none", Accumulation::kFloat32, 1, false},
      {"ema:0.5", "strict", Accumulation::kFloat32, 2, true},
  };
  for (const Case& c : cases) {
    FilterConfig config;
    config.capacity = 1u << 12;
    config.fingerprint_bits = 24;
    config.frames = 3;
    config.second_moments = true;
    config.temporal = ParseTemporal(c.temporal);
    config.eviction = ParseEviction(c.eviction);
    config.accumulation = c.accumulation;
    config.levels = c.levels;
    config.compaction = c.compacting ? Compaction::kOccupiedList : Compaction::kNone;
    const CrosscheckReport report = checker.CheckFrames(frames, config, EmulatorOptions{});
    EXPECT_TRUE(report.Passed()) << config.ToString() << ": " << report.FirstFailure();
  }
}

}  // namespace
}  // namespace hpsf::testing
