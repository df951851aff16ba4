// Level 3's image judgement (verifier/contract/image_check): every correct emulated run's image, fast or faithful,
// fixed64 or float32, crowded or not, is the resolve of its own table; an image one float ulp off in fixed64,
// or resolved with a wrong count or without a record in float32, is caught.
#include "verifier/contract/image_check.h"

#include <bit>
#include <optional>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "core/resolve.h"
#include "emulated/emulated_filter.h"
#include "property_tests/traced_batch.h"

namespace hpsf::testing {
namespace {

const RecordBatch& Cornell() {
  static const RecordBatch batch = TracedBatch("cornell", 24, 4);
  return batch;
}

EmulatedRun FastRun(Accumulation accumulation) {
  FilterConfig config;
  config.capacity = 1u << 12;
  config.accumulation = accumulation;
  return EmulatedFilter(Cornell(), config, EmulatorOptions{});
}

RC_GTEST_PROP(ImageCheck, EveryCorrectRunIsTheResolveOfItsTable, ()) {
  FilterConfig config;
  config.capacity = 1u << *rc::gen::inRange(5, 13);  // from crowded (failures, aliases) to roomy
  config.probe_limit = *rc::gen::inRange(1u, 17u);
  config.fingerprint_bits = *rc::gen::element(8u, 12u, 32u);
  config.accumulation = *rc::gen::element(Accumulation::kFixed64, Accumulation::kFloat32);
  EmulatorOptions options;
  if (*rc::gen::arbitrary<bool>()) {
    options.mode = simt::Mode::kFaithful;
    options.warp_size = *rc::gen::element(8u, 32u);
    options.schedule = "random:" + std::to_string(*rc::gen::inRange(0, 1000));
  }
  const EmulatedRun run = EmulatedFilter(Cornell(), config, options);
  const std::vector<std::string> problems = CheckImageAgainstTable(Cornell(), run);
  RC_ASSERT(problems.empty());
}

TEST(ImageCheck, CatchesAFixed64ImageOneUlpOff) {
  EmulatedRun run = FastRun(Accumulation::kFixed64);
  ASSERT_TRUE(CheckImageAgainstTable(Cornell(), run).empty());
  float& pixel = run.image.pixels[300].y;
  pixel = std::nextafter(pixel, 2.0f * pixel + 1.0f);
  const std::vector<std::string> problems = CheckImageAgainstTable(Cornell(), run);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("pixel 300 channel 1"), std::string::npos) << problems[0];
}

// The float32 image resolved as a defective pass would: each average over one record more than the slot holds,
// or a pixel that leaves out its first sample.
TEST(ImageCheck, CatchesAFloat32ResolveWithAWrongCountOrAMissingRecord) {
  const RecordBatch& batch = Cornell();
  EmulatedRun run = FastRun(Accumulation::kFloat32);
  ASSERT_TRUE(CheckImageAgainstTable(batch, run).empty());
  std::vector<std::optional<glm::dvec3>> averages(batch.records.size()), plus_one(batch.records.size());
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    const std::uint32_t slot = run.placements[i];
    if (slot >= run.table.capacity) continue;
    const auto& sum = run.table.float_sums[slot];
    const glm::dvec3 s(sum[0], sum[1], sum[2]);
    averages[i] = s / double(run.table.counts[slot]);
    plus_one[i] = s / double(run.table.counts[slot] + 1);
  }
  EmulatedRun wrong_count = run;
  wrong_count.image = ResolvePixels(batch, plus_one);
  EXPECT_FALSE(CheckImageAgainstTable(batch, wrong_count).empty());

  RecordBatch without_first = batch;  // the same table, resolved without the first sample of every pixel
  for (std::size_t p = 0; p < batch.records.size() / batch.samples_per_pixel; ++p) {
    without_first.records[p * batch.samples_per_pixel].radiance_before = glm::vec4(0.0f);
    without_first.records[p * batch.samples_per_pixel].throughput = glm::vec4(0.0f);
  }
  EmulatedRun missing = run;
  missing.image = ResolvePixels(without_first, averages);
  EXPECT_FALSE(CheckImageAgainstTable(batch, missing).empty());
  run.image = ResolvePixels(batch, averages);  // the same resolve, every record in: holds
  EXPECT_TRUE(CheckImageAgainstTable(batch, run).empty());
}

}  // namespace
}  // namespace hpsf::testing
