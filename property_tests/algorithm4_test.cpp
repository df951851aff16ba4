// Meijer's Algorithm 4 as written (docs/design/defects.md, "Meijer's Algorithm 4"; emulated/defect_injection.h,
// kAlgorithm4AsWritten; the shader accumulate_ALGORITHM_4.spv), run under several filtered bounces beside the correct
// insertion: what it does to the image's mean on the furnace and the Cornell box, and whether it explains the
// over-brightening Meijer reports for nHPSF (§5.3). Label `bounces`.

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "property_tests/transport_furnace.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_backend.h"
#include "verifier/contract/contract_levels.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf::testing {
namespace {

double MeanOf(const Image& image) {
  double sum = 0.0;
  for (const glm::vec3& p : image.pixels) sum += double(p.x) + double(p.y) + double(p.z);
  return sum / (3.0 * double(image.pixels.size()));
}

std::uint64_t SlotsUsed(const HashTableDump& table) {
  return std::uint64_t(std::count_if(table.counts.begin(), table.counts.end(), [](std::uint64_t c) { return c > 0; }));
}

// One worker thread: which record claims which slot follows the order of the adds, which is then fixed.
EmulatorOptions OneThread() {
  EmulatorOptions options;
  options.threads = 1;
  return options;
}

struct SequenceMeans {
  std::vector<double> correct, algorithm4;
  std::uint64_t correct_slots = 0, algorithm4_slots = 0, cells = 0;
};

// The frames through the reference (the correct insertion, which the emulator's matches bit for bit in fixed64) and
// through the emulator with Algorithm 4, one table each.
SequenceMeans RunBoth(const std::vector<RecordBatch>& frames, FilterConfig config) {
  SequenceMeans means;
  ReferenceBackend reference;
  EmulatedBackend correct(OneThread());
  EmulatedBackend algorithm4(OneThread(), KernelWithDefect(Defect::kAlgorithm4AsWritten));
  for (const RecordBatch& batch : frames) {
    config.frame = batch.frame;
    means.correct.push_back(MeanOf(reference.FilterFrame(batch, config)));
    correct.FilterFrame(batch, config);
    means.algorithm4.push_back(MeanOf(algorithm4.FilterFrame(batch, config)));
  }
  means.cells = reference.LastExactResult()->cells.size();
  means.correct_slots = SlotsUsed(correct.run().table);
  means.algorithm4_slots = SlotsUsed(algorithm4.run().table);
  return means;
}

void Print(const std::string& scene, const SequenceMeans& m) {
  for (std::size_t k = 0; k < m.correct.size(); ++k) {
    std::printf("%s, frame %zu: image mean %.5f correct, %.5f Algorithm 4\n", scene.c_str(), k, m.correct[k],
                m.algorithm4[k]);
  }
  std::printf("%s: %llu cells; slots used %llu correct, %llu Algorithm 4\n", scene.c_str(), (unsigned long long)m.cells,
              (unsigned long long)m.correct_slots, (unsigned long long)m.algorithm4_slots);
}

// Algorithm 4 adds a record to its cell and again to the next free slot, which it claims for the same cell: the
// checker names the second add on either backend (a slot holding the identity lies before it in the window).
TEST(Algorithm4, FailsTheContractAsAnEmulatorKernelAndAsAShader) {
  const RecordBatch batch = TracedFurnaceFrames(1, 1, 16, 2)[0];
  FilterConfig config;
  config.capacity = 4096;
  const CrosscheckReport emulated = CrosscheckEmulated(batch, config, EmulatorOptions{}, Defect::kAlgorithm4AsWritten);
  EXPECT_EQ(emulated.FirstFailure().rfind("level 2 tables", 0), 0u) << emulated.FirstFailure();
  EXPECT_NE(emulated.FirstFailure().find("earlier slot of the window empty or matching"), std::string::npos)
      << emulated.FirstFailure();
  VulkanBackendOptions shader;
  shader.accumulate_spv = std::string(HPSF_SHADER_VARIANT_DIR) + "/accumulate_ALGORITHM_4.spv";
  const std::vector<RecordBatch> frames = {batch};
  const CrosscheckReport vulkan =
      Crosschecker({"reference", "vulkan"}, Defect::kNone, shader).CheckFrames(frames, config, {});
  EXPECT_EQ(vulkan.FirstFailure().rfind("level 2 tables", 0), 0u) << vulkan.FirstFailure();
  EXPECT_NE(vulkan.FirstFailure().find("earlier slot of the window empty or matching"), std::string::npos)
      << vulkan.FirstFailure();
}

// The traced furnace (a = 1/2, e = 1: the limit is 2) with 3 filtered vertices, transported over 8 frames in an
// integrating table of 2^16 slots. Every add is a record's sums with one count, so each slot's average is a mean of
// records' values, each below the limit in expectation: Algorithm 4 cannot make a cell brighter than the light its
// records carry. But a record resolves from the slot it claimed in its own frame, which holds that frame's records
// alone (its own and the later ones of its cell): the image follows the newest frame, which carries one bounce more
// than the frames before it, ahead of the integrating table's mean, towards the limit and never past it.
TEST(Algorithm4, UnderTheTransportTheFurnaceStaysBelowItsLimit) {
  FilterConfig config;
  config.transport = true;
  config.frames = 8;
  config.capacity = 1u << 16;
  const SequenceMeans m = RunBoth(TracedFurnaceFrames(3, 8, 32, 4), config);
  Print("furnace", m);
  for (std::size_t k = 0; k < m.correct.size(); ++k) {
    EXPECT_LE(m.algorithm4[k], 2.0 + 0.005) << "frame " << k;
    EXPECT_LE(m.correct[k], 2.0 + 0.005) << "frame " << k;
    if (k > 0) {
      EXPECT_GT(m.algorithm4[k], m.correct[k]) << "frame " << k;
    }
  }
  EXPECT_GT(m.algorithm4_slots, 2 * m.correct_slots);
}

// The Cornell box with 2 filtered vertices, transported over 8 frames in an integrating table of 2^16 slots: the same
// effects as in the furnace, on a scene with shadows (docs/design/algorithm.md, "Meijer's Algorithm 4").
TEST(Algorithm4, UnderTheTransportTheCornellBoxRunsAheadOfTheIntegratingMean) {
  const std::vector<RecordBatch> frames = TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell.json"), 32, 4, 8, 2);
  FilterConfig config;
  config.transport = true;
  config.frames = 8;
  config.capacity = 1u << 16;
  const SequenceMeans m = RunBoth(frames, config);
  Print("cornell", m);
  for (std::size_t k = 1; k < m.correct.size(); ++k) EXPECT_GT(m.algorithm4[k], m.correct[k]) << "frame " << k;
  EXPECT_GT(m.algorithm4_slots, 2 * m.correct_slots);
}

}  // namespace
}  // namespace hpsf::testing
