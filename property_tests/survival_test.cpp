// Variance-aware path survival (--survival, core/survival.h), label `adaptive`.
//
// Survival thins each path at its primary vertex: given the paths (the same seed traces the same paths with and without
// it, since the decision draws a random dimension of its own), a record either adds 0 or its light divided by its
// probability p. That makes the tests exact in their theory:
// - record by record, a record of the frame with survival is 0 or the same record's light without it divided by the p
//   its view gives, and everything else about it (its vertex, throughput, radiance_before) is the same bits;
// - the sum of a frame's contributions is unbiased given the paths: E = sum c, Var = sum c^2 (1 - p) / p. The test
//   rejects |z| > 4 (a false alarm of 6e-5 per channel and rule under the normal approximation, with 16,384 records
//   a frame). The alternative it rejects, survival without the reweighting, moves the sum by sum c (1 - p): measured,
//   2 standard deviations where a rule culls 48 paths of the furnace's 16,384, 15 to 43 where it culls 500 or more
//   (printed), so the test has power where a rule culls; the variant itself is run at one such rule and fails it;
// - the culled count is binomial given the probabilities, held to |z| < 4 likewise;
// - the furnace's image mean after survival equals plain filtering's across 8 seeds (two-sample t of 14 degrees of
//   freedom, rejected at |t| > 5: a false alarm of 2e-4), and the image's variance across seeds rises as the
//   floor falls, as theory says; the biased variant fails the same t-test;
// - forced on a first frame, with no table to read, every path survives and the records are the same bits.

#include "core/survival.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend.h"
#include "core/error.h"
#include "core/filter_config.h"
#include "core/footprint.h"
#include "core/previous_table_view.h"
#include "emulated/emulated_backend.h"
#include "property_tests/own_table_frames.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_backend.h"
#include "reference/reference_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kSize = 64, kSpp = 4;

FilterConfig SurvivalConfig(const std::string& rule) {
  FilterConfig config;
  config.second_moments = true;
  config.frames = 2;
  config.survival = ParseSurvival(rule);
  return config;
}

TraceOptions Trace(std::uint32_t frame, std::uint32_t seed = 1) {
  TraceOptions trace;
  trace.width = trace.height = kSize;
  trace.samples_per_pixel = kSpp;
  trace.frame = frame;
  trace.seed = seed;
  return trace;
}

PreviousTableView ViewOf(const FilterConfig& config, const Scene& scene, const FilterResult& previous) {
  const double fov = scene.camera.fov_y_degrees * 3.14159265358979323846 / 180.0;
  const KeyParams params =
      MakeKeyParams(config, FootprintScale(config.filter_width_px, fov, kSize), kSize * kSize * kSpp);
  return PreviousTableView(config, params, previous);
}

// A sequence's second frame traced with and without survival, from the same first frame's table.
struct SecondFrame {
  std::vector<Record> plain, survived;
  std::vector<double> p;  // each record's probability, from the view
  TraceStats plain_stats, survived_stats;
};

SecondFrame TraceSecondFrame(const Scene& scene, FilterConfig config, std::uint32_t seed = 1) {
  const RecordBatch first = TraceRecords(scene, Trace(0, seed)).batch;
  const FilterResult table = ReferenceFilter(first, config);
  config.frame = 1;
  const PreviousTableView view = ViewOf(config, scene, table);
  const TraceResult plain = TraceRecords(scene, Trace(1, seed));
  const TraceResult survived = TraceRecords(scene, Trace(1, seed), {}, nullptr, &view);
  SecondFrame f{plain.batch.records, survived.batch.records, {}, plain.stats, survived.stats};
  for (const Record& r : f.plain) f.p.push_back(shared::RecordHasVertex(r) ? view.Probability(r) : 1.0);
  return f;
}

TEST(Survival, TheFunctionsAreSchipeksWithAFloor) {
  const SurvivalParams linear = ParseSurvival("linear:1:3");
  EXPECT_EQ(SurvivalProbability(linear, 0.0), 0.0625);  // eq. 4.1 gives 0: the floor
  EXPECT_EQ(SurvivalProbability(linear, 2.0), 0.5);
  EXPECT_EQ(SurvivalProbability(linear, 5.0), 1.0);
  const SurvivalParams smooth = ParseSurvival("smooth:1:3:0.125");
  EXPECT_EQ(smooth.floor, 0.125);
  EXPECT_EQ(SurvivalProbability(smooth, 2.0), 0.5);  // eq. 4.2 at the thresholds' midpoint: smoothstep of one half
  double last = 0.0;
  for (double v = 0.0; v < 20.0; v += 0.01) {
    const double p = SurvivalProbability(smooth, v);
    EXPECT_GE(p, last) << v;
    EXPECT_GE(p, 0.125) << v;
    EXPECT_LE(p, 1.0) << v;
    last = p;
  }
  EXPECT_EQ(last, 1.0);
  EXPECT_EQ(ParseSurvival("off"), SurvivalParams{});
  EXPECT_EQ(ParseSurvival(linear.ToString()), linear);
  for (const char* bad : {"on", "linear", "linear:1", "linear:3:1", "linear:1:1", "linear:-1:1", "linear:a:b",
                          "linear:1:2:0", "linear:1:2:1.5", "linear:1:2:3:4", "smooth:0:9", "linear:0:inf"}) {
    try {
      ParseSurvival(bad);
      ADD_FAILURE() << bad << " parsed";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--survival: ", 0), 0u) << e.what();
    }
  }
  FilterConfig without_moments;
  without_moments.survival = linear;
  EXPECT_THROW(without_moments.Validate(), ConfigError);
}

// Record by record: a record is its plain twin with 0 or its light divided by p, and the frame's sums are unbiased
// given the paths, on the furnace and the Cornell box, at rules that cull from a few to most of the paths.
TEST(Survival, ThinsEachPathByItsProbabilityAndReweightsTheSurvivors) {
  for (const char* name : {"furnace", "cornell"}) {
    const Scene scene = LoadScene(name);
    for (const char* rule : {"linear:0.001:0.01", "linear:0.01:0.1:0.25", "smooth:0:0.05", "linear:1:2"}) {
      const SecondFrame f = TraceSecondFrame(scene, SurvivalConfig(rule));
      const std::string where = std::string(name) + ", " + rule;
      std::uint64_t culled_lit = 0;  // culled among the records whose plain twin holds light (the others read 0 anyway)
      double expected_culled = 0.0, culled_variance = 0.0, expected_culled_lit = 0.0, culled_lit_variance = 0.0;
      glm::dvec3 plain_sum(0.0), survived_sum(0.0), variance(0.0), biased_shift(0.0);
      for (std::size_t i = 0; i < f.plain.size(); ++i) {
        const Record& a = f.plain[i];
        const Record& b = f.survived[i];
        const double p = f.p[i];
        ASSERT_EQ(a.position, b.position) << where << ", record " << i;
        ASSERT_EQ(a.path, b.path) << where << ", record " << i;
        ASSERT_EQ(a.throughput, b.throughput) << where << ", record " << i;
        ASSERT_EQ(a.radiance_before, b.radiance_before) << where << ", record " << i;
        if (!shared::RecordHasVertex(a)) continue;
        expected_culled += 1.0 - p;
        culled_variance += p * (1.0 - p);
        const bool lit = !(glm::vec3(a.contribution) == glm::vec3(0.0f));
        const bool survived = !(glm::vec3(b.contribution) == glm::vec3(0.0f));
        if (lit) {
          expected_culled_lit += 1.0 - p;
          culled_lit_variance += p * (1.0 - p);
          culled_lit += !survived;
        }
        for (int c = 0; c < 3; ++c) {
          if (survived) {
            const double want = double(a.contribution[c]) / p;
            ASSERT_LE(std::abs(double(b.contribution[c]) - want), 1e-6 * want) << where << ", record " << i;
          }
          plain_sum[c] += a.contribution[c];
          survived_sum[c] += b.contribution[c];
          variance[c] += double(a.contribution[c]) * a.contribution[c] * (1.0 - p) / p;
          biased_shift[c] += a.contribution[c] * (1.0 - p);
        }
      }
      EXPECT_LT(f.survived_stats.Rays(), f.plain_stats.Rays()) << where;
      EXPECT_EQ(f.survived_stats.camera_rays, f.plain_stats.camera_rays) << where;
      const std::uint64_t culled = f.survived_stats.culled;
      for (const auto& [observed, expected, spread] :
           {std::tuple{double(culled), expected_culled, culled_variance},
            std::tuple{double(culled_lit), expected_culled_lit, culled_lit_variance}}) {
        EXPECT_LT(std::abs(observed - expected), 4.0 * std::sqrt(std::max(spread, 1e-300)))
            << where << ": " << observed << " culled, " << expected << " expected";
      }
      for (int c = 0; c < 3; ++c) {
        const double z = (survived_sum[c] - plain_sum[c]) / std::sqrt(variance[c]);
        EXPECT_LT(std::abs(z), 4.0) << where << ", channel " << c;
        if (c == 0) {
          std::printf(
              "%s: %llu of %zu paths culled (%.0f expected), z %.2f; without the reweighting the sum moves by "
              "%.0f standard deviations\n",
              where.c_str(), (unsigned long long)culled, f.plain.size(), expected_culled, z,
              biased_shift[c] / std::sqrt(variance[c]));
        }
      }
    }
  }
}

// The variant without the reweighting, at a rule that culls two thirds of the Cornell box's paths: its sum is far
// outside the |z| < 4 that the correct one holds.
TEST(Survival, WithoutTheReweightingTheSumIsBiased) {
  FilterConfig config = SurvivalConfig("linear:0.01:0.1:0.25");
  config.survival.reweight = false;
  const SecondFrame f = TraceSecondFrame(LoadScene("cornell"), config);
  double plain_sum = 0.0, survived_sum = 0.0, variance = 0.0;
  for (std::size_t i = 0; i < f.plain.size(); ++i) {
    if (!shared::RecordHasVertex(f.plain[i])) continue;
    const double c = f.plain[i].contribution[0], p = f.p[i];
    plain_sum += c;
    survived_sum += f.survived[i].contribution[0];
    variance += c * c * (1.0 - p) / p;
  }
  const double z = (survived_sum - plain_sum) / std::sqrt(variance);
  std::printf("without the reweighting: z %.1f\n", z);
  EXPECT_LT(z, -4.0);
}

// The furnace's image after a second frame with survival, across 8 seeds, against plain filtering's: equal means
// within |t| < 5, the spread rising as the floor falls; the variant without the reweighting fails the same test.
TEST(Survival, TheFurnacesImageMeanIsUnbiasedAndItsSpreadRisesAsFewerPathsSurvive) {
  const Scene scene = LoadScene("furnace");
  struct Moments {
    double mean = 0.0, variance = 0.0;
  };
  const auto image_means = [&](const std::string& rule, bool reweight) {
    std::vector<double> means;
    for (std::uint32_t seed = 1; seed <= 8; ++seed) {
      FilterConfig config = SurvivalConfig(rule);
      config.seed = seed;
      config.survival.reweight = reweight;
      const RecordBatch first = TraceRecords(scene, Trace(0, seed)).batch;
      const FilterResult table = ReferenceFilter(first, config);
      config.frame = 1;
      const PreviousTableView view = ViewOf(config, scene, table);
      const RecordBatch second =
          TraceRecords(scene, Trace(1, seed), {}, nullptr, config.survival.enabled() ? &view : nullptr).batch;
      const Image image = ReferenceFilter(second, config, &table).image;
      double sum = 0.0;
      for (const glm::vec3& p : image.pixels) sum += (double(p.x) + p.y + p.z) / 3.0;
      means.push_back(sum / double(image.pixels.size()));
    }
    Moments m;
    for (double x : means) m.mean += x / double(means.size());
    for (double x : means) m.variance += (x - m.mean) * (x - m.mean) / double(means.size() - 1);
    return m;
  };
  const auto t_of = [](const Moments& a, const Moments& b) {
    return (a.mean - b.mean) / std::sqrt((a.variance + b.variance) / 8.0);
  };
  // Rules whose lower threshold lies above every cell's variance: each resolved cell's paths survive at the floor.
  const Moments plain = image_means("off", true);
  std::printf("plain: image mean %.5f, variance across seeds %.3g\n", plain.mean, plain.variance);
  double last_variance = plain.variance;
  for (const char* rule : {"linear:10:20:0.5", "linear:10:20:0.25", "linear:10:20:0.0625"}) {
    const Moments m = image_means(rule, true);
    const double t = t_of(m, plain);
    std::printf("%s: image mean %.5f, variance across seeds %.3g, t %.2f\n", rule, m.mean, m.variance, t);
    EXPECT_LT(std::abs(t), 5.0) << rule;
    EXPECT_GT(m.variance, last_variance) << rule;
    last_variance = m.variance;
  }
  const Moments biased = image_means("linear:10:20:0.25", false);
  const double t = t_of(biased, plain);
  std::printf("linear:10:20:0.25 without the reweighting: image mean %.5f, t %.1f\n", biased.mean, t);
  EXPECT_GT(std::abs(t), 5.0);
}

// `hpsf render`'s loop on each backend, each deciding by its own table: in fixed64, with nothing aliased, the three
// tables are the same cells, so the decisions, the records and the images are the same bits on all three.
TEST(Survival, EachBackendDecidingByItsOwnTableMakesTheSameImage) {
  const Scene scene = LoadScene("cornell");
  FilterConfig config = SurvivalConfig("linear:0.001:0.01");
  config.frames = 3;
  config.capacity = 1u << 16;
  ReferenceBackend reference;
  EmulatedBackend emulated{EmulatorOptions{}};
  VulkanBackend vulkan{TestDevice(StagingPolicy::kNever)};
  std::vector<OwnTableFrames> runs;
  for (Backend* backend : std::initializer_list<Backend*>{&reference, &emulated, &vulkan}) {
    runs.push_back(FilterDecidingByOwnTable(*backend, scene, config, [](std::uint32_t k) { return Trace(k); }));
  }
  EXPECT_GT(runs[0].culled, 0u);
  EXPECT_EQ(runs[1].culled, runs[0].culled);
  EXPECT_EQ(runs[2].culled, runs[0].culled);
  EXPECT_EQ(runs[1].image.pixels, runs[0].image.pixels) << "emulated";
  EXPECT_EQ(runs[2].image.pixels, runs[0].image.pixels) << "vulkan";
  std::printf("%llu paths culled over 3 frames on every backend\n", (unsigned long long)runs[0].culled);
}

// Effect planning: forced on a sequence's first frame, survival reads no table, every path survives with p = 1 and
// the records are the same bits as without it.
TEST(Survival, ForcedOnAFirstFrameEveryPathSurvivesAndNoBitChanges) {
  const Scene scene = LoadScene("cornell");
  const FilterConfig config = SurvivalConfig("linear:0:0.001");
  const double fov = scene.camera.fov_y_degrees * 3.14159265358979323846 / 180.0;
  const PreviousTableView nothing(
      config, MakeKeyParams(config, FootprintScale(config.filter_width_px, fov, kSize), kSize * kSize * kSpp));
  const TraceResult plain = TraceRecords(scene, Trace(0));
  const TraceResult forced = TraceRecords(scene, Trace(0), {}, nullptr, &nothing);
  EXPECT_EQ(forced.stats.culled, 0u);
  EXPECT_EQ(forced.stats.Rays(), plain.stats.Rays());
  ASSERT_EQ(forced.batch.records.size(), plain.batch.records.size());
  for (std::size_t i = 0; i < plain.batch.records.size(); ++i) {
    ASSERT_EQ(std::memcmp(&forced.batch.records[i], &plain.batch.records[i], sizeof(Record)), 0) << "record " << i;
  }
}

}  // namespace
}  // namespace hpsf::testing
