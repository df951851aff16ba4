#include "tracer/path_tracer.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "core/input_check.h"
#include "reference/reference_filter.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

TraceOptions SmallOptions(std::uint32_t size, std::uint32_t spp, int max_depth = 8) {
  TraceOptions o;
  o.width = o.height = size;
  o.samples_per_pixel = spp;
  o.max_depth = max_depth;
  return o;
}

glm::dvec3 RecordValue(const Record& r) {
  glm::dvec3 v(r.radiance_before.x, r.radiance_before.y, r.radiance_before.z);
  if (shared::RecordHasVertex(r)) v += glm::dvec3(r.throughput) * glm::dvec3(r.contribution);
  return v;
}

struct MeanAndVariance {
  double mean = 0.0, variance = 0.0;
};

MeanAndVariance Moments(const std::vector<double>& x) {
  MeanAndVariance m;
  for (double v : x) m.mean += v;
  m.mean /= double(x.size());
  for (double v : x) m.variance += (v - m.mean) * (v - m.mean);
  m.variance /= double(x.size() - 1);
  return m;
}

double PixelVariance(const Image& image) {
  std::vector<double> luminance;
  for (const glm::vec3& p : image.pixels) luminance.push_back((p.x + p.y + p.z) / 3.0);
  return Moments(luminance).variance;
}

// The furnace's radiance is exactly 2 everywhere with unbounded depth. The 99.9% confidence interval of the
// mean comes from the sample variance of the per-sample values (z = 3.29).
TEST(Furnace, MeanRadianceIsTwoFilteredAndUnfiltered) {
  const TraceResult traced = TraceRecords(LoadScene("furnace"), SmallOptions(48, 16, -1));
  std::vector<double> samples;
  for (const Record& r : traced.batch.records) {
    ASSERT_EQ(CheckRecordInputs(r), InputVerdict::kAccepted);
    samples.push_back(RecordValue(r).y);
  }
  const MeanAndVariance m = Moments(samples);
  const double half_width = 3.29 * std::sqrt(m.variance / double(samples.size()));
  EXPECT_NEAR(m.mean, 2.0, half_width) << "variance " << m.variance;
  EXPECT_LT(half_width, 0.05) << "the interval must be narrow enough to mean something";

  const Image unfiltered = UnfilteredImage(traced.batch);
  const FilterResult filtered = ReferenceFilter(traced.batch, FilterConfig{});
  double filtered_mean = 0.0;
  for (const glm::vec3& p : filtered.image.pixels) filtered_mean += p.y;
  filtered_mean /= double(filtered.image.pixels.size());
  // The throughput is the same for every record (albedo 0.5), so filtering moves light between samples but
  // keeps the mean: the same interval applies.
  EXPECT_NEAR(filtered_mean, 2.0, half_width);
  EXPECT_LT(PixelVariance(filtered.image), 0.5 * PixelVariance(unfiltered));
}

// A closed furnace of albedo a and emission e sees L = e (1 + a + a^2 + ...) everywhere: a path limited to D
// surface vertices must give exactly the first D terms, e (1 - a^D) / (1 - a), and unbounded depth the whole
// series e / (1 - a).
struct FurnaceCase {
  glm::dvec3 albedo, emission;
};

double SeriesTerms(double albedo, double emission, int depth) {
  if (depth < 0) return emission / (1.0 - albedo);
  double sum = 0.0, power = 1.0;
  for (int k = 0; k < depth; ++k, power *= albedo) sum += emission * power;
  return sum;
}

// Three furnaces (among them the built-in one and a zero albedo channel) at depths 1..8 and unbounded: 27 runs
// of 3 channels, 81 comparisons. Each interval is the mean's, from the per-sample variance, Sidak-corrected so
// that the whole family holds at 99.9% (z = 4.37 per comparison). The seed is fixed, so the verdict never
// changes between runs. Power: the test asserts that a bias of a quarter of the first omitted term e a^D (what
// an MIS-weighted next-event estimate at the last vertex added) is detected with probability 0.95 or more
// wherever that term is larger than 0.02, which is 42 of the 81 comparisons (64x64 pixels at 16 spp).
TEST(Furnace, DepthLimitTruncatesTheSeriesFilteredAndUnfiltered) {
  const std::vector<FurnaceCase> cases = {
      {{0.5, 0.5, 0.5}, {1.0, 1.0, 1.0}}, {{0.8, 0.3, 0.0}, {1.0, 2.0, 0.5}}, {{0.9, 0.6, 0.15}, {0.25, 0.5, 3.0}}};
  const double z = 4.37;  // two-sided normal quantile at 1 - (1 - (0.999)^(1/81)) / 2
  const double z_power = 1.645;
  int powered = 0;
  for (const FurnaceCase& furnace : cases) {
    Scene scene = LoadScene("furnace");
    scene.materials[0].albedo = glm::vec3(furnace.albedo);
    scene.materials[0].emission = glm::vec3(furnace.emission);
    for (int depth : {1, 2, 3, 4, 5, 6, 7, 8, -1}) {
      SCOPED_TRACE("albedo " + std::to_string(furnace.albedo.x) + " " + std::to_string(furnace.albedo.y) + " " +
                   std::to_string(furnace.albedo.z) + ", depth " + std::to_string(depth));
      const TraceResult traced = TraceRecords(scene, SmallOptions(64, 16, depth));
      const Image filtered = ReferenceFilter(traced.batch, FilterConfig{}).image;
      for (int c = 0; c < 3; ++c) {
        std::vector<double> samples;
        for (const Record& r : traced.batch.records) samples.push_back(RecordValue(r)[c]);
        const MeanAndVariance m = Moments(samples);
        const double standard_error = std::sqrt(m.variance / double(samples.size()));
        // Records hold floats: a zero-variance channel still carries their rounding.
        const double expected = SeriesTerms(furnace.albedo[c], furnace.emission[c], depth), rounding = 1e-6 * expected;
        EXPECT_NEAR(m.mean, expected, z * standard_error + rounding)
            << "unfiltered, channel " << c << ", variance " << m.variance;
        // Every record's throughput is the albedo: filtering moves light between samples but keeps the mean,
        // so the same interval applies.
        double filtered_mean = 0.0;
        for (const glm::vec3& p : filtered.pixels) filtered_mean += p[c];
        filtered_mean /= double(filtered.pixels.size());
        EXPECT_NEAR(filtered_mean, expected, z * standard_error + rounding) << "filtered, channel " << c;
        if (depth < 0) continue;
        const double next_term = furnace.emission[c] * std::pow(furnace.albedo[c], depth);
        if (next_term > 0.02) {
          EXPECT_LT((z + z_power) * standard_error, 0.25 * next_term) << "channel " << c << ": too little power";
          ++powered;
        }
      }
    }
  }
  EXPECT_EQ(powered, 42) << "the power statement covers other comparisons than it says";
}

TEST(PathTracer, OneRecordPerSampleInPixelSampleOrder) {
  const TraceResult traced = TraceRecords(LoadScene("cornell"), SmallOptions(24, 3));
  ASSERT_EQ(traced.batch.records.size(), 24u * 24u * 3u);
  for (std::size_t i = 0; i < traced.batch.records.size(); ++i) {
    EXPECT_EQ(shared::RecordPixel(traced.batch.records[i]), i / 3);
    EXPECT_EQ(shared::RecordSample(traced.batch.records[i]), i % 3);
  }
  EXPECT_GT(traced.stats.camera_rays, 0u);
}

TEST(PathTracer, BitsDoNotDependOnTheThreadCount) {
  const Scene scene = LoadScene("cornell");
  TraceOptions one = SmallOptions(40, 2), two = one;
  one.threads = 1;
  two.threads = 2;
  const RecordBatch a = TraceRecords(scene, one).batch, b = TraceRecords(scene, two).batch,
                    c = TraceRecords(scene, two).batch;
  ASSERT_EQ(a.records.size(), b.records.size());
  EXPECT_EQ(std::memcmp(a.records.data(), b.records.data(), a.records.size() * sizeof(Record)), 0);
  EXPECT_EQ(std::memcmp(b.records.data(), c.records.data(), b.records.size() * sizeof(Record)), 0);
  const Image ia = ReferenceFilter(a, FilterConfig{}).image, ib = ReferenceFilter(b, FilterConfig{}).image;
  EXPECT_TRUE(SameBits(ia, ib));
}

TEST(PathTracer, SkyHitsAreSamplesOfTheirPixel) {
  const Scene scene = ParseScene(R"({"hpsf_scene": 1, "sky": [0.25, 0.5, 1],
      "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y_degrees": 40},
      "materials": [{"name": "grey", "albedo": [0.5, 0.5, 0.5]}],
      "shapes": [{"material": "grey", "quad": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]}]})",
                                 "sky-test", ".");
  const TraceResult traced = TraceRecords(scene, SmallOptions(16, 4, 1));
  const Image image = UnfilteredImage(traced.batch);
  // A corner pixel sees only sky: all its samples are records without a vertex, and its value is the sky.
  EXPECT_EQ(image.At(0, 0), glm::vec3(0.25f, 0.5f, 1.0f));
  for (std::uint32_t s = 0; s < 4; ++s) EXPECT_FALSE(shared::RecordHasVertex(traced.batch.records[s]));
  const FilterResult filtered = ReferenceFilter(traced.batch, FilterConfig{});
  EXPECT_EQ(filtered.image.At(0, 0), glm::vec3(0.25f, 0.5f, 1.0f));
  EXPECT_GT(filtered.stats.records_without_vertex, 0u);
  EXPECT_EQ(filtered.stats.records_with_vertex + filtered.stats.records_without_vertex, filtered.stats.records);
}

}  // namespace
}  // namespace hpsf

namespace hpsf {
namespace {

// --filter-bounce moves the filter vertex along the same paths: the records split each path's radiance
// differently, but unfiltered they add up to the same pixels.
TEST(PathTracer, LaterFilterBounceSplitsTheSamePaths) {
  const Scene scene = LoadScene("cornell");
  TraceOptions first = SmallOptions(24, 2), second = first;
  second.filter_bounce = 1;
  const RecordBatch a = TraceRecords(scene, first).batch, b = TraceRecords(scene, second).batch;
  int later = 0;
  for (const Record& r : b.records) {
    if (!shared::RecordHasVertex(r)) continue;
    EXPECT_EQ(shared::RecordBounce(r), 1u);
    ++later;
  }
  EXPECT_GT(later, int(b.records.size()) / 2);
  const Image ia = UnfilteredImage(a), ib = UnfilteredImage(b);
  for (std::size_t i = 0; i < ia.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ib.pixels[i][c], ia.pixels[i][c], 1e-4f * (1.0f + ia.pixels[i][c])) << i;
  }
}

}  // namespace
}  // namespace hpsf

namespace hpsf {
namespace {

// Several filtered bounces (core/transport.h): with `scattered`, each path ends at the vertex it scatters to from its
// filter vertex and records it. The records are those of paths of filter bounce + 2 vertices, bit for bit (the same
// random numbers); each scattered vertex continues its own record's path (its pixel and sample, the next bounce, the
// filter vertex as its previous vertex, the path length to it) and carries the albedo it reached, the cosine-sampled
// bounce's weight being 1: 0.5 in the furnace. Paths that end before scattering have none.
TEST(PathTracer, ScatteredVerticesContinueTheirRecordsPaths) {
  for (const std::uint32_t filter_bounce : {0u, 1u}) {
    TraceOptions scattered = SmallOptions(24, 2), truncated = scattered;
    scattered.scattered = true;
    scattered.filter_bounce = truncated.filter_bounce = filter_bounce;
    truncated.max_depth = int(filter_bounce) + 2;
    const Scene furnace = LoadScene("furnace");
    const RecordBatch a = TraceRecords(furnace, scattered).batch, b = TraceRecords(furnace, truncated).batch;
    ASSERT_EQ(a.records.size(), b.records.size());
    EXPECT_EQ(std::memcmp(a.records.data(), b.records.data(), a.records.size() * sizeof(Record)), 0);
    EXPECT_TRUE(b.scattered.empty());
    ASSERT_EQ(a.scattered.size(), a.records.size());
    for (std::size_t i = 0; i < a.records.size(); ++i) {
      const Record& r = a.records[i];
      const Record& s = a.scattered[i];
      ASSERT_TRUE(shared::RecordHasVertex(r) && shared::RecordHasVertex(s)) << i;  // the furnace is closed
      EXPECT_EQ(shared::RecordPixel(s), shared::RecordPixel(r));
      EXPECT_EQ(shared::RecordSample(s), shared::RecordSample(r));
      EXPECT_EQ(shared::RecordBounce(s), filter_bounce + 1);
      EXPECT_EQ(glm::vec3(s.previous), glm::vec3(r.position));
      EXPECT_GT(s.position.w, r.position.w);  // the path length grew by the segment to the filter vertex
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.throughput[c], 0.5f, 1e-6f) << i;
    }
  }
  // An open scene: a path that leaves for the sky scatters nowhere, and its scattered vertex has no vertex flag.
  const Scene open = ParseScene(R"({"hpsf_scene": 1, "sky": [1, 1, 1],
      "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y_degrees": 20},
      "materials": [{"name": "grey", "albedo": [0.5, 0.5, 0.5]}],
      "shapes": [{"material": "grey", "quad": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]}]})",
                                "open", ".");
  TraceOptions o = SmallOptions(8, 2);
  o.scattered = true;
  const RecordBatch batch = TraceRecords(open, o).batch;
  int hits = 0;
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    if (!shared::RecordHasVertex(batch.records[i])) continue;
    ++hits;  // a lone quad: every bounce from it leaves for the sky
    EXPECT_FALSE(shared::RecordHasVertex(batch.scattered[i])) << i;
  }
  EXPECT_GT(hits, 0);
}

}  // namespace
}  // namespace hpsf

namespace hpsf {
namespace {

// With several filtered vertices, record i's path continues in its deeper records: deeper record j (the path's filtered
// vertex j + 1) lies where the previous filtered vertex scattered to, and each filtered vertex's record holds the light
// of one vertex further. Chained back with the transport weights, c_0 + w_1 (c_1 + w_2 (c_2 + ...)), they give the
// value of the same path traced whole to the last one's scattered vertex (--max-depth filter bounce + N + 1), up to
// float rounding.
TEST(PathTracer, DeeperRecordsSplitTheSamePathsVertexByVertex) {
  const Scene scene = LoadScene("cornell");
  for (const std::uint32_t filtered : {2u, 3u}) {
    TraceOptions split = SmallOptions(16, 2), whole = split;
    split.scattered = true;
    split.filtered_vertices = filtered;
    whole.max_depth = int(filtered) + 1;
    const RecordBatch a = TraceRecords(scene, split).batch, b = TraceRecords(scene, whole).batch;
    const std::size_t n = a.records.size(), more = filtered - 1;
    ASSERT_EQ(a.deeper.size(), n * more);
    ASSERT_EQ(a.scattered.size(), n + n * more);
    int chained = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Record& r = a.records[i];
      if (!shared::RecordHasVertex(r)) continue;
      // Record j of the chain (0: the pixel record), and the vertex it scattered to.
      const auto chain = [&](std::size_t j) -> const Record& { return j == 0 ? r : a.deeper[i * more + j - 1]; };
      const auto next = [&](std::size_t j) -> const Record& {
        return j == 0 ? a.scattered[i] : a.scattered[n + i * more + j - 1];
      };
      glm::dvec3 tail(0.0);
      for (std::size_t j = filtered; j-- > 0;) {
        const Record& v = chain(j);
        if (!shared::RecordHasVertex(v)) {
          EXPECT_FALSE(shared::RecordHasVertex(next(j - 1))) << i << ": a deeper record past the path's end";
          tail = glm::dvec3(0.0);
          continue;
        }
        EXPECT_EQ(shared::RecordBounce(v), j);
        if (j > 0) {
          EXPECT_EQ(glm::vec3(next(j - 1).position), glm::vec3(v.position)) << i;
          EXPECT_EQ(glm::vec3(v.previous), glm::vec3(chain(j - 1).position)) << i;
        }
        const glm::dvec3 weight = shared::RecordHasVertex(next(j)) ? glm::dvec3(next(j).throughput) : glm::dvec3(0.0);
        tail = glm::dvec3(v.contribution) + weight * tail;
      }
      const glm::dvec3 value = glm::dvec3(r.radiance_before) + glm::dvec3(r.throughput) * tail;
      const glm::dvec3 expected = RecordValue(b.records[i]);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(value[c], expected[c], 1e-5 * (1.0 + expected[c])) << i;
      ++chained;
    }
    EXPECT_GT(chained, int(n) / 2);
  }
}

}  // namespace
}  // namespace hpsf
