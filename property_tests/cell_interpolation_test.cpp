// Variance-aware cell interpolation (--interpolation, core/shared/cell_interpolation.h), label `adaptive`:
// - the weights are Schipek's eqs. 4.4 and 4.5, in [0, 1], and bad rules are refused by name;
// - the rule's extremes are exact on every backend: a weight of 1 everywhere resolves plain HPSF's image bit for bit,
//   a weight of 0 everywhere path tracing's (each record's own light), since w a + (1 - w) c with w = 1 or 0 is exact;
// - in between, the three backends resolve the same bits in fixed64 (one frame and a blending sequence), and the image
//   lies between the extremes' where they differ.

#include "core/cell_interpolation.h"

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend.h"
#include "core/error.h"
#include "core/filter_config.h"
#include "core/shared/cell_interpolation.h"
#include "emulated/emulated_backend.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_backend.h"
#include "reference/reference_filter.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

TEST(CellInterpolation, TheWeightsAreSchipeksWithinZeroAndOne) {
  EXPECT_EQ(shared::InterpolationWeight(shared::kInterpolationStep, 1.0, 3.0, 0.5), 1.0);
  EXPECT_EQ(shared::InterpolationWeight(shared::kInterpolationStep, 1.0, 3.0, 2.0), 0.0);  // eq. 4.4: the path
  EXPECT_EQ(shared::InterpolationWeight(shared::kInterpolationStep, 1.0, 3.0, 3.0), 1.0);
  // Eq. 4.5: (V1 - V0) / 8 at the midpoint, rising towards 1 on either side.
  EXPECT_EQ(shared::InterpolationWeight(shared::kInterpolationSmooth, 1.0, 3.0, 2.0), 0.25);
  double last = 0.25;
  for (double v = 2.0; v < 50.0; v += 0.01) {
    const double w = shared::InterpolationWeight(shared::kInterpolationSmooth, 1.0, 3.0, v);
    const double mirrored = shared::InterpolationWeight(shared::kInterpolationSmooth, 1.0, 3.0, 4.0 - v);
    EXPECT_GE(w, last) << v;
    EXPECT_LE(w, 1.0) << v;
    EXPECT_GE(mirrored, 0.0) << v;
    EXPECT_LE(mirrored, 1.0) << v;
    last = w;
  }
  EXPECT_GT(last, 0.999);
  // The broken variant "weights outside [0, 1]": eq. 4.5 for thresholds 8 or more apart gives w above 1 near their
  // midpoint (1 - (V1 - V0) / 8 < 0), a blend that extrapolates past the cell. The parser refuses such rules, and the
  // weight is clamped wherever it is computed, so a rule that reaches a shader some other way still blends.
  for (double v = 0.0; v < 20.0; v += 0.05) {
    const double w = shared::InterpolationWeight(shared::kInterpolationSmooth, 0.0, 12.0, v);
    EXPECT_GE(w, 0.0) << v;
    EXPECT_LE(w, 1.0) << v;
  }
  EXPECT_EQ(ParseInterpolation("off"), CellInterpolation{});
  const CellInterpolation smooth = ParseInterpolation("smooth:0.001:0.01");
  EXPECT_EQ(ParseInterpolation(smooth.ToString()), smooth);
  for (const char* bad : {"on", "step", "step:1", "step:3:1", "step:1:1", "step:-1:1", "step:a:b", "step:1:2:3",
                          "smooth:0:8", "linear:0:1", "step:0:inf"}) {
    try {
      ParseInterpolation(bad);
      ADD_FAILURE() << bad << " parsed";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--interpolation: ", 0), 0u) << e.what();
    }
  }
  FilterConfig without_moments;
  without_moments.interpolation = smooth;
  EXPECT_THROW(without_moments.Validate(), ConfigError);
}

FilterConfig InterpolatingConfig(const std::string& rule) {
  FilterConfig config;
  config.second_moments = true;
  config.capacity = 1u << 16;
  config.interpolation = ParseInterpolation(rule);
  return config;
}

// Each backend's image of the frames under the config, through one table.
std::vector<Image> Images(const std::vector<RecordBatch>& frames, FilterConfig config) {
  ReferenceBackend reference;
  EmulatedBackend emulated{EmulatorOptions{}};
  VulkanBackend vulkan{TestDevice(StagingPolicy::kNever)};
  std::vector<Image> images;
  for (Backend* backend : std::initializer_list<Backend*>{&reference, &emulated, &vulkan}) {
    Image image;
    for (const RecordBatch& batch : frames) {
      config.frame = batch.frame;
      image = backend->FilterFrame(batch, config);
    }
    images.push_back(image);
  }
  return images;
}

TEST(CellInterpolation, TheRulesExtremesAreHpsfAndPathTracingBitForBit) {
  const RecordBatch batch = TracedBatch(HPSF_SCENES_DIR "/cornell.json", 48, 4);
  FilterConfig plain;
  plain.second_moments = true;
  plain.capacity = 1u << 16;
  const Image hpsf = ReferenceFilter(batch, plain).image;
  const Image path_tracing = UnfilteredImage(batch);
  const std::vector<Image> cell = Images({batch}, InterpolatingConfig("step:1e9:2e9"));  // no cell in range: w = 1
  // Every cell in range, variance 0 included: w = 0 (a lower threshold below 0, which the option refuses, so that a
  // cell of one sample, variance 0, takes the path too).
  FilterConfig everywhere = InterpolatingConfig("step:0:1e9");
  everywhere.interpolation.v0 = -1.0;
  const std::vector<Image> path = Images({batch}, everywhere);
  const char* names[] = {"reference", "emulated", "vulkan"};
  for (int b = 0; b < 3; ++b) {
    EXPECT_EQ(cell[b].pixels, hpsf.pixels) << names[b];
    EXPECT_EQ(path[b].pixels, path_tracing.pixels) << names[b];
  }
  EXPECT_NE(hpsf.pixels, path_tracing.pixels);
}

TEST(CellInterpolation, EveryBackendResolvesTheSameBitsBetweenTheExtremes) {
  const Scene scene = LoadScene(HPSF_SCENES_DIR "/cornell.json");
  const std::vector<RecordBatch> frames = TracedFrames(scene, 32, 2, 3);
  for (const char* rule : {"smooth:0.001:0.01", "step:0.002:0.02"}) {
    FilterConfig config = InterpolatingConfig(rule);
    config.frames = 3;
    config.temporal = ParseTemporal("ema:0.5");
    const std::vector<Image> images = Images(frames, config);
    EXPECT_EQ(images[1].pixels, images[0].pixels) << rule << ", emulated";
    EXPECT_EQ(images[2].pixels, images[0].pixels) << rule << ", vulkan";
    FilterConfig plain = config;
    plain.interpolation = {};
    const std::vector<Image> hpsf = Images(frames, plain);
    EXPECT_NE(images[0].pixels, hpsf[0].pixels) << rule << ": the rule changed no pixel";
  }
}

}  // namespace
}  // namespace hpsf::testing
