// Path survival decided from the table being accumulated (emulated/broken_survival.h, D10's cousin), label `adaptive`.
//
// hpsf's tracer decides each path's survival before any pass of the frame, from the table the frame before left. A
// team that fuses its tracer and its accumulate decides inside the accumulate's launch, from the table the launch adds
// to: the variance it reads is whatever the frame's adds that came first made it. The emulator runs that team
// (SurvivalDuringAccumulate): the paths traced in full, each record's decision taken in the launch from its own cell.
// Its oracle is the same team reading the table before the frame (DecidedBeforeTheFrame): the same lights, draws and
// rule, so the two add the same bits wherever the launch reads a cell as the frame before left it.

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/footprint.h"
#include "core/previous_table_view.h"
#include "emulated/broken_survival.h"
#include "property_tests/constructed_cells.h"
#include "property_tests/racing_schedules.h"
#include "reference/reference_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "verifier/contract/contract_levels.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kSeed = 1;

KeyParams KeyParamsOf(const FilterConfig& config, const RecordBatch& batch) {
  return MakeKeyParams(config, FootprintScale(config.filter_width_px, batch.fov_y_radians, batch.height),
                       static_cast<std::uint32_t>(batch.records.size() + batch.deeper.size()));
}

std::vector<glm::vec3> LightsOf(const RecordBatch& batch) {
  std::vector<glm::vec3> lights;
  for (const Record& r : batch.records) lights.push_back(glm::vec3(r.contribution));
  return lights;
}

CrosscheckReport Judge(const std::vector<RecordBatch>& frames, const FilterConfig& config,
                       const EmulatorOptions& emulator) {
  return CrosscheckEmulatedSequence(frames, config, emulator);
}

// The Cornell box's frames at 8 x 8 pixels and 4 samples, as the fused team traces them (`fused`) and as it would add
// them reading the table before each frame, the reference's (the frames the contract judges).
std::vector<RecordBatch> CornellFrames(const FilterConfig& base, SurvivalInPass& fused) {
  const Scene scene = LoadScene("cornell");
  fused.seed = kSeed;
  std::vector<RecordBatch> frames;
  std::optional<FilterResult> previous;
  for (std::uint32_t k = 0; k < base.frames; ++k) {
    TraceOptions trace;
    trace.width = trace.height = 8;
    trace.samples_per_pixel = 4;
    trace.frame = k;
    trace.seed = kSeed;
    const RecordBatch traced = TraceRecords(scene, trace).batch;
    fused.traced[k] = LightsOf(traced);
    FilterConfig config = base;
    config.frame = k;
    const KeyParams params = KeyParamsOf(config, traced);
    const PreviousTableView view =
        previous ? PreviousTableView(config, params, *previous) : PreviousTableView(config, params);
    frames.push_back(DecidedBeforeTheFrame(traced, view, kSeed));
    previous = ReferenceFilter(frames.back(), config, previous ? &*previous : nullptr);
  }
  return frames;
}

// Over the Cornell box's 3 frames, the faithful emulator's 40 schedules (random and PCT of depth 3, warps of 4) and
// fast mode's serial order: hpsf's own accumulate of the frames passes under every one; the team deciding inside the
// launch is caught under some (a cell's sums differ from its records': the launch added other decisions than the
// frame before's table makes).
TEST(SurvivalInPass, ADecisionReadFromTheTableBeingAccumulatedIsARaceTheSchedulesFind) {
  FilterConfig config;
  config.second_moments = true;
  config.survival = ParseSurvival("linear:0.001:0.05:0.25");
  config.frames = 3;
  config.capacity = 1u << 12;
  SurvivalInPass fused;
  const std::vector<RecordBatch> frames = CornellFrames(config, fused);
  std::uint64_t culled = 0, records = 0;
  for (const RecordBatch& frame : frames) {
    for (std::size_t i = 0; i < frame.records.size(); ++i) {
      records += shared::RecordHasVertex(frame.records[i]);
      culled += shared::RecordHasVertex(frame.records[i]) && glm::vec3(frame.records[i].contribution) == glm::vec3(0) &&
                !(fused.traced[frame.frame][i] == glm::vec3(0));
    }
  }
  std::printf("the frames' decisions from the table before each: %llu of %llu lit paths culled\n",
              (unsigned long long)culled, (unsigned long long)records);
  ASSERT_GT(culled, 0u) << "the rule culls nothing: the decisions cannot differ";
  const std::vector<EmulatorOptions> schedules = RacingSchedules();
  int caught = 0;
  for (EmulatorOptions options : schedules) {
    const std::string name = options.mode == simt::Mode::kFast ? "fast, one thread" : options.schedule;
    const CrosscheckReport correct = Judge(frames, config, options);
    EXPECT_TRUE(correct.Passed()) << name << ": " << correct.FirstFailure();
    options.survival_in_pass = &fused;
    const CrosscheckReport racing = Judge(frames, config, options);
    if (!racing.Passed()) {
      EXPECT_EQ(racing.FirstFailure().rfind("level 2", 0), 0u) << name << ": " << racing.FirstFailure();
      if (caught++ == 0) std::printf("%s: %s\n", name.c_str(), racing.FirstFailure().c_str());
    }
  }
  std::printf("survival decided from the table being accumulated: caught under %d of %zu schedules\n", caught,
              schedules.size());
  EXPECT_GT(caught, 0);
}

// Every order of one record's decision and another sample's add to its cell, enumerated. Frame 0 places cell A with
// two samples (a variance); in frame 1, thread 0 (a record of A) decides by A's variance and adds, and thread 1 (a
// deeper record of A, which decides nothing) adds. The exhaustive schedule (warps of one lane) runs every order of
// the two threads' operations. The decision reads the frame before's A only where all of thread 1's adds come after
// thread 0's reads; any other order reads a variance of three samples (or a torn one). The draw is one that survives
// at the floor, so every order's decision survives and adds its light divided by the p it read. The oracle is the
// decision from the table before the frame, the same bits under every schedule; hpsf's accumulate of it passes every
// order.
TEST(SurvivalInPass, EveryOrderOfADecisionAndAnAddToItsCellIsExplored) {
  FilterConfig config = ConstructedConfig(8, 4);
  config.second_moments = true;
  config.survival = ParseSurvival("linear:0:0.002:0.25");
  config.frames = 2;
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 0u; });
  const RecordBatch frame0 = BatchOfCells({a, a});  // y = 1.625 and 1.875
  RecordBatch frame1 = BatchOfCells({a});
  frame1.frame = 1;
  frame1.deeper = BatchOfCells({a, a}).records;  // the second, of y = 1.875
  frame1.deeper.erase(frame1.deeper.begin());
  SurvivalInPass fused;
  fused.traced[1] = LightsOf(frame1);
  for (fused.seed = 1; SurvivalDraws(frame1, fused.seed)[0] >= 0.25f; ++fused.seed) {
  }
  const EmulatedRun first = EmulatedFilter(frame0, config, EmulatorOptions{});
  config.frame = 1;
  const RecordBatch decided =
      DecidedBeforeTheFrame(frame1, PreviousTableView(config, KeyParamsOf(config, frame1), first.table), fused.seed);
  const double p = double(frame1.records[0].contribution.x) / decided.records[0].contribution.x;
  ASSERT_GT(p, 0.25) << "the table before the frame reads a variance the rule's ramp does not reach";
  ASSERT_LT(p, 1.0) << "the table before the frame reads a variance the rule's ramp does not reach";
  const EmulatedRun expected = EmulatedFilter(decided, config, EmulatorOptions{}, AccumulateKernel, &first.table);
  auto explore = [&](const SurvivalInPass* in_pass) {
    EmulatorOptions options;
    options.survival_in_pass = in_pass;
    return ExploreEveryOrder(options, [&](const EmulatorOptions& each) {
      return EmulatedFilter(decided, config, each, AccumulateKernel, &first.table).table.fixed_sums !=
             expected.table.fixed_sums;
    });
  };
  const Exploration correct = explore(nullptr);
  const Exploration racing = explore(&fused);
  std::printf(
      "one decision and one add to its cell, exhaustive (p %.4f before the frame): hpsf's accumulate %llu schedules, "
      "all equal; deciding from the table being accumulated caught under %llu of %llu\n",
      p, (unsigned long long)correct.schedules, (unsigned long long)racing.caught,
      (unsigned long long)racing.schedules);
  EXPECT_EQ(correct.caught, 0u);
  EXPECT_GT(racing.caught, 0u);
  EXPECT_LT(racing.caught, racing.schedules) << "no order read A as the frame before left it";
}

}  // namespace
}  // namespace hpsf::testing
