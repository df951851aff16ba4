// Adaptive path graphs (--path-graph, core/path_graph.h), label `adaptive`.
//
// A path gathers tp^2 V from the cells of its vertices in the table before the frame and is cut where the sum would
// pass the bound: 1 - alpha of the rest of its light is the cell's average, alpha the path's. The tests:
// - the step alone: the sum meets the bound exactly where it cuts (alpha^2 local = bound - variance, to rounding), and
//   never passes it; the broken variant that cuts only after the bound is passed does pass it;
// - a traced frame: no path gathers more than the bound (the tracer's own account, TraceStats::graph_variance_max),
//   which the broken variant breaks on the Cornell box;
// - the cut changes a record's own light only, never what its cell adds: the records are path tracing's, bit for bit;
// - the extremes are exact: a bound of 0 gives every path whose filter vertex's cell has a variance that cell's
//   average as its own light, bit for bit; an unbounded graph, or one forced on a first frame with no table, gives
//   path tracing's own lights, bit for bit;
// - the furnace's image mean is unbiased at every bound (two-sample t of 14 degrees of freedom over 8 seeds against
//   path tracing, rejected at |t| > 5: a false alarm of 2e-4), and its spread across seeds falls as the bound falls;
// - each backend deciding by its own table makes the same image.

#include "core/path_graph.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend.h"
#include "core/error.h"
#include "core/filter_config.h"
#include "core/footprint.h"
#include "core/previous_table_view.h"
#include "core/shared/rng.h"
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

FilterConfig GraphConfig(const std::string& bound) {
  FilterConfig config;
  config.second_moments = true;
  config.frames = 2;
  config.path_graph = ParsePathGraph(bound);
  config.interpolation = ParseInterpolation("path");
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

KeyParams ParamsOf(const FilterConfig& config, const Scene& scene) {
  const double fov = scene.camera.fov_y_degrees * 3.14159265358979323846 / 180.0;
  return MakeKeyParams(config, FootprintScale(config.filter_width_px, fov, kSize), kSize * kSize * kSpp);
}

// A sequence's second frame traced with the graph and without, from the same first frame's table.
struct SecondFrame {
  FilterResult table;
  std::vector<Record> plain, graphed;
  std::vector<glm::vec4> own_light;  // the graphed frame's
  TraceStats plain_stats, graphed_stats;
};

SecondFrame TraceSecondFrame(const Scene& scene, FilterConfig config, std::uint32_t seed = 1) {
  SecondFrame f;
  f.table = ReferenceFilter(TraceRecords(scene, Trace(0, seed)).batch, config);
  config.frame = 1;
  const PreviousTableView view(config, ParamsOf(config, scene), f.table);
  const TraceResult plain = TraceRecords(scene, Trace(1, seed));
  const TraceResult graphed = TraceRecords(scene, Trace(1, seed), {}, nullptr, &view);
  f.plain = plain.batch.records;
  f.graphed = graphed.batch.records;
  f.own_light = graphed.batch.own_light;
  f.plain_stats = plain.stats;
  f.graphed_stats = graphed.stats;
  return f;
}

// A counter-RNG float in [0, 1) for the step's inputs.
double RandomUnit(std::uint32_t dimension, std::uint32_t i) {
  return shared::RandomFloatFromPrefix(shared::RngPrefix(shared::RngCounter{7, 0, i, 0, 0}), dimension);
}

bool SameBits(const Record& a, const Record& b) { return std::memcmp(&a, &b, sizeof(Record)) == 0; }

TEST(PathGraph, TheStepMeetsTheBoundWhereItCutsAndNeverPassesIt) {
  const PathGraphParams params = ParsePathGraph("0.25");
  EXPECT_EQ(params.bound, 0.25);
  std::uint32_t cuts = 0;
  for (std::uint32_t i = 0; i < 10000; ++i) {
    const double variance = 0.25 * RandomUnit(1, i), local = 0.5 * RandomUnit(2, i);
    const PathGraphStep step = StepPathGraph(params, variance, local);
    EXPECT_LE(step.variance, 0.25);
    if (!step.cut) {
      EXPECT_EQ(step.alpha, 1.0);
      EXPECT_EQ(step.variance, variance + local);
      continue;
    }
    ++cuts;
    EXPECT_GE(step.alpha, 0.0);
    EXPECT_LT(step.alpha, 1.0);
    EXPECT_EQ(step.variance, 0.25);
    // Eq. 4.15: what the path still adds, alpha^2 local, fills the bound.
    EXPECT_NEAR(variance + step.alpha * step.alpha * local, 0.25, 1e-15);
  }
  EXPECT_GT(cuts, 1000u);
  EXPECT_EQ(StepPathGraph(ParsePathGraph("0"), 0.0, 1e-30).alpha, 0.0);  // a bound of 0: the cell takes all
  EXPECT_FALSE(StepPathGraph(ParsePathGraph("0"), 0.0, 0.0).cut);        // a cell without variance cuts nothing

  PathGraphParams late = params;  // the broken variant passes the bound, then cuts at the next cell
  late.cut_before_exceeding = false;
  const PathGraphStep over = StepPathGraph(late, 0.2, 0.1);
  EXPECT_FALSE(over.cut);
  EXPECT_GT(over.variance, 0.25);
  EXPECT_TRUE(StepPathGraph(late, over.variance, 0.1).cut);

  EXPECT_FALSE(ParsePathGraph("off").enabled);
  EXPECT_EQ(ParsePathGraph(params.ToString()), params);
  for (const char* bad : {"on", "-1", "inf", "nan", "1:2", "", "0.1x"}) {
    try {
      ParsePathGraph(bad);
      ADD_FAILURE() << bad << " parsed";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--path-graph: ", 0), 0u) << e.what();
    }
  }
  FilterConfig without_moments;
  without_moments.path_graph = params;
  EXPECT_THROW(without_moments.Validate(), ConfigError);
  FilterConfig with_transport = GraphConfig("0.25");
  with_transport.transport = true;
  EXPECT_THROW(with_transport.Validate(), ConfigError);
}

// The tracer's account of each path: no path gathers more than the bound, and where paths are cut the most any
// gathered is the bound itself. The variant that cuts late passes it.
TEST(PathGraph, NoPathGathersMoreVarianceThanTheBound) {
  const Scene scene = LoadScene("cornell");
  for (const char* bound : {"0.0001", "0.001", "0.01", "0.1"}) {
    const SecondFrame f = TraceSecondFrame(scene, GraphConfig(bound));
    const double b = ParsePathGraph(bound).bound;
    std::printf("bound %s: %llu of %zu paths cut, the most gathered %.6g\n", bound,
                (unsigned long long)f.graphed_stats.cut, f.graphed.size(), f.graphed_stats.graph_variance_max);
    EXPECT_GT(f.graphed_stats.cut, 0u) << bound;
    EXPECT_EQ(f.graphed_stats.graph_variance_max, b) << bound;
    FilterConfig late = GraphConfig(bound);
    late.path_graph.cut_before_exceeding = false;
    const SecondFrame g = TraceSecondFrame(scene, late);
    std::printf("  cut after passing it: the most gathered %.6g\n", g.graphed_stats.graph_variance_max);
    EXPECT_GT(g.graphed_stats.graph_variance_max, b) << bound;
  }
}

// The cut changes a record's own light only: its contribution, which its cell adds, is the path's in full, so every
// record is path tracing's, bit for bit, and so are the rays traced. With a bound of 0 every path whose filter vertex's
// cell has a variance is cut there with alpha 0: its own light is that cell's average, rounded to float once.
TEST(PathGraph, TheCutChangesTheOwnLightOnlyAndABoundOfZeroGivesTheCellsAverage) {
  const Scene scene = LoadScene("cornell");
  FilterConfig config = GraphConfig("0");
  const SecondFrame f = TraceSecondFrame(scene, config);
  config.frame = 1;
  const PreviousTableView view(config, ParamsOf(config, scene), f.table);
  ASSERT_EQ(f.own_light.size(), f.plain.size());
  EXPECT_EQ(f.graphed_stats.Rays(), f.plain_stats.Rays());
  std::uint64_t averaged = 0, traced = 0;
  for (std::size_t i = 0; i < f.plain.size(); ++i) {
    EXPECT_TRUE(SameBits(f.plain[i], f.graphed[i])) << i;
    if (!shared::RecordHasVertex(f.plain[i])) continue;
    const std::optional<CellEstimate> cell = view.Cell(f.plain[i]);
    if (cell && cell->moments.variance > 0.0) {
      ++averaged;
      EXPECT_EQ(glm::vec3(f.own_light[i]), glm::vec3(cell->average)) << i;
    } else if (glm::vec3(f.own_light[i]) == glm::vec3(f.plain[i].contribution)) {
      ++traced;  // cut nowhere along the path
    }
  }
  std::printf("%llu paths took their filter vertex's cell's average, %llu kept their own light, %llu cut\n",
              (unsigned long long)averaged, (unsigned long long)traced, (unsigned long long)f.graphed_stats.cut);
  EXPECT_GT(averaged, f.plain.size() / 2);
  EXPECT_GE(f.graphed_stats.cut, averaged);
}

// An unbounded graph cuts nothing, and forced on a first frame it has no table to read: path tracing's records, and
// each record's own light its contribution.
TEST(PathGraph, AnUnboundedGraphOrOneWithoutATableIsPathTracingBitForBit) {
  const Scene scene = LoadScene("cornell");
  const SecondFrame f = TraceSecondFrame(scene, GraphConfig("1e300"));
  EXPECT_EQ(f.graphed_stats.cut, 0u);
  EXPECT_EQ(f.graphed_stats.Rays(), f.plain_stats.Rays());
  for (std::size_t i = 0; i < f.plain.size(); ++i) {
    EXPECT_TRUE(SameBits(f.plain[i], f.graphed[i])) << i;
    if (shared::RecordHasVertex(f.plain[i])) {
      EXPECT_EQ(f.own_light[i], f.plain[i].contribution) << i;
    }
  }

  const FilterConfig config = GraphConfig("0");
  const PreviousTableView nothing(config, ParamsOf(config, scene));
  const TraceResult plain = TraceRecords(scene, Trace(0));
  const TraceResult forced = TraceRecords(scene, Trace(0), {}, nullptr, &nothing);
  EXPECT_EQ(forced.stats.cut, 0u);
  EXPECT_EQ(forced.stats.Rays(), plain.stats.Rays());
  for (std::size_t i = 0; i < plain.batch.records.size(); ++i) {
    EXPECT_TRUE(SameBits(plain.batch.records[i], forced.batch.records[i])) << i;
    if (shared::RecordHasVertex(plain.batch.records[i])) {
      EXPECT_EQ(forced.batch.own_light[i], plain.batch.records[i].contribution) << i;
    }
  }
}

// The furnace's image (each record's own light: --interpolation path) after a second frame, across 8 seeds, against
// path tracing's: equal image means within |t| < 5 at every bound, and the noise (each pixel's variance across the
// seeds, averaged over the pixels: 4,096 pixels of 7 degrees of freedom each, so a relative standard error near 1%)
// falling as the bound falls to 1e-3. Below it, nearly every path is cut at its filter vertex's cell and the noise
// is the cells' (at 0, HPSF's): a path kept with a small alpha can lower it a little, so it need not fall further.
TEST(PathGraph, TheFurnacesImageMeanIsUnbiasedAndItsNoiseFallsWithTheBound) {
  const Scene scene = LoadScene("furnace");
  constexpr std::uint32_t kSeeds = 8;
  struct Moments {
    double mean = 0.0, variance = 0.0;  // of the image mean across seeds
    double noise = 0.0;                 // a pixel's variance across seeds, averaged over the pixels
    std::uint64_t cut = 0;
  };
  const auto measure = [&](const std::string& bound) {
    std::vector<std::vector<double>> images;
    Moments m;
    for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
      FilterConfig config = GraphConfig(bound);
      config.seed = seed;
      const FilterResult table = ReferenceFilter(TraceRecords(scene, Trace(0, seed)).batch, config);
      config.frame = 1;
      const PreviousTableView view(config, ParamsOf(config, scene), table);
      const TraceResult second =
          TraceRecords(scene, Trace(1, seed), {}, nullptr, config.path_graph.enabled ? &view : nullptr);
      m.cut += second.stats.cut;
      std::vector<double> image;
      for (const glm::vec3& p : ReferenceFilter(second.batch, config, &table).image.pixels) {
        image.push_back((double(p.x) + p.y + p.z) / 3.0);
      }
      images.push_back(std::move(image));
    }
    std::vector<double> means;
    for (const std::vector<double>& image : images) {
      double sum = 0.0;
      for (double x : image) sum += x;
      means.push_back(sum / double(image.size()));
    }
    for (double x : means) m.mean += x / kSeeds;
    for (double x : means) m.variance += (x - m.mean) * (x - m.mean) / (kSeeds - 1);
    const std::size_t pixels = images[0].size();
    for (std::size_t i = 0; i < pixels; ++i) {
      double mean = 0.0, variance = 0.0;
      for (const std::vector<double>& image : images) mean += image[i] / kSeeds;
      for (const std::vector<double>& image : images) variance += (image[i] - mean) * (image[i] - mean) / (kSeeds - 1);
      m.noise += variance / double(pixels);
    }
    return m;
  };
  const Moments traced = measure("off");
  std::printf("path tracing: image mean %.5f, noise %.3g\n", traced.mean, traced.noise);
  double last_noise = traced.noise;
  for (const char* bound : {"1e-1", "1e-2", "1e-3", "1e-4", "0"}) {
    const Moments m = measure(bound);
    const double t = (m.mean - traced.mean) / std::sqrt((m.variance + traced.variance) / kSeeds);
    std::printf("bound %s: %llu paths cut, image mean %.5f, noise %.3g, t %.2f\n", bound, (unsigned long long)m.cut,
                m.mean, m.noise, t);
    EXPECT_GT(m.cut, 0u) << bound;
    EXPECT_LT(std::abs(t), 5.0) << bound;
    if (ParsePathGraph(bound).bound >= 1e-3) {
      EXPECT_LT(m.noise, last_noise) << bound;
    }
    last_noise = m.noise;
  }
}

// `hpsf render`'s loop on each backend, each deciding by its own table: in fixed64, with nothing aliased, the three
// tables are the same cells, so the cuts, the records and the images are the same bits on all three.
TEST(PathGraph, EachBackendDecidingByItsOwnTableMakesTheSameImage) {
  const Scene scene = LoadScene("cornell");
  FilterConfig config = GraphConfig("0.001");
  config.frames = 3;
  config.capacity = 1u << 16;
  ReferenceBackend reference;
  EmulatedBackend emulated{EmulatorOptions{}};
  VulkanBackend vulkan{TestDevice(StagingPolicy::kNever)};
  std::vector<OwnTableFrames> runs;
  for (Backend* backend : std::initializer_list<Backend*>{&reference, &emulated, &vulkan}) {
    runs.push_back(FilterDecidingByOwnTable(*backend, scene, config, [](std::uint32_t k) { return Trace(k); }));
  }
  EXPECT_GT(runs[0].cut, 0u);
  EXPECT_EQ(runs[1].cut, runs[0].cut);
  EXPECT_EQ(runs[2].cut, runs[0].cut);
  EXPECT_EQ(runs[1].image.pixels, runs[0].image.pixels) << "emulated";
  EXPECT_EQ(runs[2].image.pixels, runs[0].image.pixels) << "vulkan";
  std::printf("%llu paths cut over 3 frames on every backend\n", (unsigned long long)runs[0].cut);
}

}  // namespace
}  // namespace hpsf::testing
