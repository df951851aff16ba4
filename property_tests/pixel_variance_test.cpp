// The variance estimate of verifier/metrics/pixel_variance against its oracle, the spread of the same pixel over
// independent renders: the Cornell box traced and filtered with K seeds, the empirical variance of every pixel
// and of the image mean over the seeds compared with the average of the K estimates. The within-pixel term alone
// (the naive estimate) must fail where cells are shared, which is the oracle of the cell term. Seeds are fixed, so
// each ratio is one number that never changes between runs and the test cannot flake; each band is stated with
// the spread a correct estimate's ratio has over seeds, and what a wrong estimate gives.
#include "verifier/metrics/pixel_variance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "emulated/emulated_filter.h"
#include "reference/reference_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kSize = 32;
constexpr std::uint32_t kSpp = 16;
constexpr std::uint32_t kFirstSeed = 1000;

struct SeedRun {
  Image image;
  PixelVariance variance;
};

// The Cornell box looking down at the floor, the light out of view. In the plain view the few pixels on the
// light's edge (17 against 0.5 in a pixel, by sample) hold most of the image mean's variance, and no filter changes
// them; here every pixel's noise is the cells' noise, which is what the image mean's cell term is about.
Scene CornellWithoutTheLight() {
  Scene scene = LoadScene("cornell");
  scene.camera.look_at = glm::dvec3(278.0, 0.0, 280.0);
  return scene;
}

RecordBatch Trace(const Scene& scene, std::uint32_t seed) {
  TraceOptions trace;
  trace.width = trace.height = kSize;
  trace.samples_per_pixel = kSpp;
  trace.seed = seed;
  return TraceRecords(scene, trace).batch;
}

SeedRun Filtered(const RecordBatch& batch, std::uint32_t seed) {
  FilterConfig config;
  config.seed = seed;  // the jitter's, as `hpsf render` sets it
  const FilterResult result = ReferenceFilter(batch, config);
  return {result.image, EstimatePixelVariance(batch, result.placement, result.cells.size())};
}

SeedRun Unfiltered(const RecordBatch& batch) { return {UnfilteredImage(batch), EstimatePixelVariance(batch, {}, 0)}; }

// Empirical variance over the seeds divided by the average estimate, per channel.
struct Agreement {
  glm::dvec3 pixel{0.0};     // the mean over pixels of each pixel's ratio: every pixel counts the same
  glm::dvec3 weighted{0.0};  // summed variance over summed estimate: the noisiest pixels count most
  glm::dvec3 mean{0.0};      // the image mean's
  glm::dvec3 tile{0.0};      // the mean over tiles of each tile mean's ratio (the statistical comparison's tests)
  std::string ToString() const {
    char text[320];
    std::snprintf(text, sizeof text,
                  "per pixel (%.3f, %.3f, %.3f), weighted (%.3f, %.3f, %.3f), image mean (%.3f, "
                  "%.3f, %.3f), per tile (%.3f, %.3f, %.3f)",
                  pixel.x, pixel.y, pixel.z, weighted.x, weighted.y, weighted.z, mean.x, mean.y, mean.z, tile.x, tile.y,
                  tile.z);
    return text;
  }
};

// The mean of one tile of an image, tiles of `size` pixels a side.
glm::dvec3 TileMean(const Image& image, std::uint32_t tx, std::uint32_t ty, std::uint32_t size) {
  glm::dvec3 sum(0.0);
  double k = 0.0;
  for (std::uint32_t y = ty * size; y < std::min(image.height, (ty + 1) * size); ++y) {
    for (std::uint32_t x = tx * size; x < std::min(image.width, (tx + 1) * size); ++x, k += 1.0) {
      sum += glm::dvec3(image.pixels[std::size_t(y) * image.width + x]);
    }
  }
  return sum / k;
}

// The tile means' empirical variance over the seeds against the average estimate, averaged over tiles;
// `estimate` gives one run's estimate for tile (tx, ty).
using TileEstimate = std::function<glm::dvec3(const SeedRun&, std::uint32_t, std::uint32_t)>;

glm::dvec3 TileAgreement(const std::vector<SeedRun>& runs, const TileEstimate& estimate) {
  const double k = double(runs.size());
  const PixelVariance& first = runs[0].variance;
  glm::dvec3 ratio(0.0), counted(0.0);
  for (std::uint32_t ty = 0; ty < first.tile_variance.height; ++ty) {
    for (std::uint32_t tx = 0; tx < first.tile_variance.width; ++tx) {
      glm::dvec3 mean(0.0), squares(0.0), estimated(0.0);
      for (const SeedRun& run : runs) mean += TileMean(run.image, tx, ty, first.tile_size) / k;
      for (const SeedRun& run : runs) {
        const glm::dvec3 d = TileMean(run.image, tx, ty, first.tile_size) - mean;
        squares += d * d;
        estimated += estimate(run, tx, ty) / k;
      }
      for (int c = 0; c < 3; ++c) {
        if (estimated[c] == 0.0) {  // estimated noiseless (a tile of background): it must be
          EXPECT_EQ(squares[c], 0.0) << "tile (" << tx << ", " << ty << ") channel " << c;
          continue;
        }
        ratio[c] += squares[c] / (k - 1.0) / estimated[c];
        counted[c] += 1.0;
      }
    }
  }
  return ratio / counted;
}

glm::dvec3 FullTile(const SeedRun& run, std::uint32_t tx, std::uint32_t ty) {
  return glm::dvec3(run.variance.tile_variance.pixels[std::size_t(ty) * run.variance.tile_variance.width + tx]);
}

// Each pixel's full variance summed over the tile as if pixels were independent: misses the cells they share.
glm::dvec3 IndependentPixelsTile(const SeedRun& run, std::uint32_t tx, std::uint32_t ty) {
  const std::uint32_t size = run.variance.tile_size;
  const Image& v = run.variance.variance;
  glm::dvec3 sum(0.0);
  double k = 0.0;
  for (std::uint32_t y = ty * size; y < std::min(v.height, (ty + 1) * size); ++y) {
    for (std::uint32_t x = tx * size; x < std::min(v.width, (tx + 1) * size); ++x, k += 1.0) {
      sum += glm::dvec3(v.pixels[std::size_t(y) * v.width + x]);
    }
  }
  return sum / (k * k);
}

using PixelEstimate = std::function<const Image&(const PixelVariance&)>;
using MeanEstimate = std::function<glm::dvec3(const PixelVariance&)>;

const Image& Full(const PixelVariance& v) { return v.variance; }
glm::dvec3 FullMean(const PixelVariance& v) { return v.mean_variance; }
const Image& Naive(const PixelVariance& v) { return v.within_pixel; }
glm::dvec3 NaiveMean(const PixelVariance& v) { return v.mean_within_pixel; }

glm::dvec3 At(const Image& image, std::size_t p) { return glm::dvec3(image.pixels[p]); }

Agreement Compare(const std::vector<SeedRun>& runs, const PixelEstimate& pixel_estimate = Full,
                  const MeanEstimate& mean_estimate = FullMean) {
  const double k = double(runs.size());
  const std::size_t pixels = runs[0].image.pixels.size();
  Agreement agreement;
  glm::dvec3 empirical_sum(0.0), estimate_sum(0.0), counted(0.0);
  for (std::size_t p = 0; p < pixels; ++p) {
    glm::dvec3 mean(0.0), squares(0.0), estimate(0.0);
    for (const SeedRun& run : runs) mean += At(run.image, p) / k;
    for (const SeedRun& run : runs) {
      squares += (At(run.image, p) - mean) * (At(run.image, p) - mean);
      estimate += At(pixel_estimate(run.variance), p) / k;
    }
    const glm::dvec3 empirical = squares / (k - 1.0);
    empirical_sum += empirical;
    estimate_sum += estimate;
    for (int c = 0; c < 3; ++c) {
      if (estimate[c] == 0.0) {  // estimated noiseless: it must be (a pixel every sample sees the same)
        EXPECT_EQ(empirical[c], 0.0) << "pixel " << p << " channel " << c;
        continue;
      }
      agreement.pixel[c] += empirical[c] / estimate[c];
      counted[c] += 1.0;
    }
  }
  agreement.pixel /= counted;
  agreement.weighted = empirical_sum / estimate_sum;
  std::vector<glm::dvec3> means;
  glm::dvec3 mean_of_means(0.0), estimate(0.0);
  for (const SeedRun& run : runs) {
    glm::dvec3 sum(0.0);
    for (std::size_t p = 0; p < pixels; ++p) sum += At(run.image, p);
    means.push_back(sum / double(pixels));
    mean_of_means += means.back() / k;
    estimate += mean_estimate(run.variance) / k;
  }
  glm::dvec3 squares(0.0);
  for (const glm::dvec3& m : means) squares += (m - mean_of_means) * (m - mean_of_means);
  agreement.mean = squares / (k - 1.0) / estimate;
  agreement.tile = TileAgreement(runs, FullTile);
  return agreement;
}

void ExpectWithin(const glm::dvec3& ratio, double low, double high, const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_GE(ratio[c], low) << what << ", channel " << c;
    EXPECT_LE(ratio[c], high) << what << ", channel " << c;
  }
}

void ExpectAbove(const glm::dvec3& ratio, double low, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_GT(ratio[c], low) << what << ", channel " << c;
}

// The bands. Per pixel: each pixel's empirical variance over 24 seeds has a relative spread of sqrt(2/23) = 0.29;
// the mean over 1024 pixels brings that to 0.01 for independent (unfiltered) pixels and, as cells correlate
// neighbours, to about 0.02 for filtered ones (measured over 6 sets of seeds, both views: unfiltered 0.98 to
// 1.01, filtered 0.96 to 1.00, the linearisation costing up to 4%). +-5% and +-10% are three to five times that
// spread, and tight enough to catch n for n - 1 in S2_p (a factor 16/15) and the cell noise counted twice (0.82).
// The image mean is one number per seed: its ratio has the spread of chi-square(K-1)/(K-1) widened by the heavy
// tail of the noise (measured 0.58 to 1.25); [0.4, 2.5] holds it, and the naive estimate lies above (3.1 to 7.1).
constexpr double kPixelBandFiltered = 0.10;
constexpr double kPixelBandUnfiltered = 0.05;
constexpr double kMeanLow = 0.4;
constexpr double kMeanHigh = 2.5;
// A tile mean (8x8 pixels; 16 tiles at 32x32) has the per-pixel ratio's spread over seeds without the averaging
// over 1024 pixels: sqrt(2/23) / 4 = 0.07 for independent tiles. Measured: filtered 0.89 to 0.96, unfiltered 0.98
// to 1.08; summing the pixels' variances as if independent (the cells they share left out) gives 2.8 to 3.2.
constexpr double kTileBand = 0.25;

TEST(PixelVariance, MatchesTheSpreadOverSeedsOfTheCornellBox) {
  const Scene scene = LoadScene("cornell");
  std::vector<SeedRun> filtered, unfiltered;
  for (std::uint32_t k = 0; k < 24; ++k) {
    const RecordBatch batch = Trace(scene, kFirstSeed + k);
    filtered.push_back(Filtered(batch, kFirstSeed + k));
    unfiltered.push_back(Unfiltered(batch));
  }
  const Agreement f = Compare(filtered), naive = Compare(filtered, Naive, NaiveMean), u = Compare(unfiltered);
  std::printf("filtered %s\nnaive    %s\nunfiltered %s\n", f.ToString().c_str(), naive.ToString().c_str(),
              u.ToString().c_str());
  ExpectWithin(f.pixel, 1.0 - kPixelBandFiltered, 1.0 + kPixelBandFiltered, "filtered, per pixel");
  ExpectWithin(f.weighted, 1.0 - kPixelBandFiltered, 1.0 + kPixelBandFiltered, "filtered, weighted");
  ExpectWithin(f.mean, kMeanLow, kMeanHigh, "filtered, image mean");
  ExpectWithin(u.pixel, 1.0 - kPixelBandUnfiltered, 1.0 + kPixelBandUnfiltered, "unfiltered, per pixel");
  ExpectWithin(u.weighted, 1.0 - kPixelBandFiltered, 1.0 + kPixelBandFiltered, "unfiltered, weighted");
  ExpectWithin(u.mean, kMeanLow, kMeanHigh, "unfiltered, image mean");
  // The naive estimate sees a cell's noise only where a pixel's samples read different cells: a typical filtered
  // pixel's variance is about 1.8 times it (measured 1.71 to 1.91). The light's edge pixels, which no cell
  // touches, dominate the weighted ratio and the image mean here, so only the per-pixel ratio shows it.
  ExpectAbove(naive.pixel, 1.0 + 3.0 * kPixelBandFiltered, "the naive estimate must fall short per pixel");
  const glm::dvec3 independent = TileAgreement(filtered, IndependentPixelsTile);
  std::printf("tiles as independent pixels (%.3f, %.3f, %.3f)\n", independent.x, independent.y, independent.z);
  ExpectWithin(f.tile, 1.0 - kTileBand, 1.0 + kTileBand, "filtered, per tile");
  ExpectWithin(u.tile, 1.0 - kTileBand, 1.0 + kTileBand, "unfiltered, per tile");
  ExpectAbove(independent, 1.0 + 2.0 * kTileBand, "tiles without the cells their pixels share must fall short");
}

TEST(PixelVariance, ImageMeanCountsTheCellsThatPixelsShare) {
  const Scene scene = CornellWithoutTheLight();
  std::vector<SeedRun> filtered;
  for (std::uint32_t k = 0; k < 48; ++k) filtered.push_back(Filtered(Trace(scene, kFirstSeed + k), kFirstSeed + k));
  const Agreement f = Compare(filtered), naive = Compare(filtered, Naive, NaiveMean);
  std::printf("filtered %s\nnaive    %s\n", f.ToString().c_str(), naive.ToString().c_str());
  ExpectWithin(f.pixel, 1.0 - kPixelBandFiltered, 1.0 + kPixelBandFiltered, "per pixel");
  ExpectWithin(f.mean, kMeanLow, kMeanHigh, "image mean");
  // Pixels that share a cell move together: the naive sum of per-pixel terms misses most of the image mean's
  // variance, and the statistical comparison's mean test would reject consistent renders.
  ExpectAbove(naive.mean, kMeanHigh, "the naive estimate must fall short for the image mean");
  const glm::dvec3 independent = TileAgreement(filtered, IndependentPixelsTile);
  std::printf("tiles as independent pixels (%.3f, %.3f, %.3f)\n", independent.x, independent.y, independent.z);
  ExpectWithin(f.tile, 1.0 - kTileBand, 1.0 + kTileBand, "per tile");
  ExpectAbove(independent, 1.0 + 2.0 * kTileBand, "tiles without the cells their pixels share must fall short");
}

// A record by hand: a vertex with this contribution and throughput (every channel the same but blue's
// contribution, which is 1 throughout, so blue's cell has no noise).
Record Vertex(std::uint32_t pixel, std::uint32_t sample, float contribution, float throughput) {
  VertexSample v;
  v.pixel = pixel;
  v.sample = sample;
  v.position = glm::vec3(1.0f, 2.0f, 3.0f);
  v.previous = glm::vec3(1.0f, 2.0f, 0.0f);
  v.contribution = glm::vec3(contribution, contribution, 1.0f);
  v.throughput = glm::vec3(throughput);
  return MakeVertexRecord(v);
}

RecordBatch TwoPixels(std::vector<Record> records) {
  RecordBatch batch;
  batch.width = 2;
  batch.height = 1;
  batch.samples_per_pixel = 2;
  batch.records = std::move(records);
  return batch;
}

void ExpectVec(const glm::dvec3& actual, const glm::dvec3& expected, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], 1e-12 * std::abs(expected[c])) << what << " " << c;
}

// A pixel is stored as float: the exact value rounded once.
void ExpectPixel(const glm::vec3& actual, const glm::dvec3& expected, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_EQ(actual[c], float(expected[c])) << what << " " << c;
}

// Cell 0 holds contributions 1, 3, 5 (mean 3, s2 4, so q = s2 / N = 4/3); pixel 0 reads it twice with throughput
// 1, pixel 1 once with throughput 2 and has a sample without a vertex of radiance 4.
//  pixel 0: values 3, 3: S2 = 0; one pair in the cell: q (T^2 - A) / (n (n - 1)) = 4/3 (4 - 2) / 2 = 4/3.
//  pixel 1: values 6, 4: S2 = 2, S2 / n = 1; no pair.
//  image mean: sum S2 / n / P^2 = 1/4; pairs: pixel 0's (8/3) / (n - 1) + the cell's q (T_c^2 - A_c) =
//  4/3 (16 - 6) = 40/3, in all 16, over (n P)^2 = 16: 1. So 1.25. Blue: no cell noise, pixel 1's S2 / n = 1.
TEST(PixelVariance, AConstructedBatchHasItsHandComputedVariance) {
  const RecordBatch batch = TwoPixels({Vertex(0, 0, 1.0f, 1.0f), Vertex(0, 1, 3.0f, 1.0f), Vertex(1, 0, 5.0f, 2.0f),
                                       MakeRecordWithoutVertex(1, 1, glm::vec3(4.0f, 4.0f, 4.0f))});
  const std::uint32_t none = 7;  // >= the group count: no group
  const std::vector<std::uint32_t> groups = {2, 2, 2, none};
  const PixelVariance v = EstimatePixelVariance(batch, groups, 3);
  SCOPED_TRACE(v.ToString());
  ExpectPixel(v.variance.pixels[0], glm::dvec3(4.0 / 3.0, 4.0 / 3.0, 0.0), "pixel 0");
  ExpectPixel(v.variance.pixels[1], glm::dvec3(1.0, 1.0, 1.0), "pixel 1");
  ExpectPixel(v.within_pixel.pixels[0], glm::dvec3(0.0), "pixel 0 within");
  ExpectVec(v.mean_variance, glm::dvec3(1.25, 1.25, 0.25), "image mean");
  ExpectVec(v.mean_within_pixel, glm::dvec3(0.25), "image mean within");
  // One 8x8 tile holds the whole image: its variance is the image mean's; tiles of one pixel are the pixels.
  ASSERT_EQ(v.tile_variance.pixels.size(), 1u);
  ExpectPixel(v.tile_variance.pixels[0], glm::dvec3(1.25, 1.25, 0.25), "the one tile");
  const PixelVariance single = EstimatePixelVariance(batch, groups, 3, 1);
  ASSERT_EQ(single.tile_variance.width, 2u);
  ExpectPixel(single.tile_variance.pixels[0], glm::dvec3(4.0 / 3.0, 4.0 / 3.0, 0.0), "tile of pixel 0");
  ExpectPixel(single.tile_variance.pixels[1], glm::dvec3(1.0, 1.0, 1.0), "tile of pixel 1");

  // Unfiltered, each record its own: pixel 0 values 1, 3 (S2 2, so 1); pixel 1 values 10, 4 (S2 18, so 9).
  const PixelVariance u = EstimatePixelVariance(batch, {}, 0);
  ExpectPixel(u.variance.pixels[0], glm::dvec3(1.0, 1.0, 0.0), "unfiltered pixel 0");
  ExpectPixel(u.variance.pixels[1], glm::dvec3(9.0, 9.0, 1.0), "unfiltered pixel 1");
  ExpectVec(u.mean_variance, glm::dvec3(2.5, 2.5, 0.25), "unfiltered image mean");
}

// A rejected record (a negative contribution) counts 0 in its pixel and joins no cell, whatever its entry says, as
// no backend places it; a group past the count is no group.
TEST(PixelVariance, ARejectedRecordIsZeroAndInNoCell) {
  const RecordBatch batch = TwoPixels(
      {Vertex(0, 0, 1.0f, 1.0f), Vertex(0, 1, 3.0f, 1.0f), Vertex(1, 0, 5.0f, 2.0f), Vertex(1, 1, -1.0f, 1.0f)});
  const PixelVariance v = EstimatePixelVariance(batch, std::vector<std::uint32_t>{0, 0, 1, 0}, 2);
  // Cell 0 is {1, 3}: mean 2, s2 2, q 1; cell 1 is {5} alone: no noise of its own. Pixel 0: values 2, 2, one pair:
  // 1 (4 - 2) / 2 = 1. Pixel 1: values 10 and 0: S2 50, so 25 (blue: 2 and 0, so 1).
  ExpectPixel(v.variance.pixels[0], glm::dvec3(1.0, 1.0, 0.0), "pixel 0");
  ExpectPixel(v.variance.pixels[1], glm::dvec3(25.0, 25.0, 1.0), "pixel 1");
}

TEST(PixelVariance, OneSamplePerPixelHasNoWithinPixelTerm) {
  RecordBatch batch = TwoPixels({Vertex(0, 0, 1.0f, 1.0f), Vertex(1, 0, 3.0f, 1.0f)});
  batch.samples_per_pixel = 1;
  const PixelVariance v = EstimatePixelVariance(batch, std::vector<std::uint32_t>{0, 0}, 1);
  for (const glm::vec3& p : v.variance.pixels) EXPECT_EQ(p, glm::vec3(0.0f));
  // Only the pair across the two pixels is left: q = 2 / 2 = 1, (T^2 - A) = 2, over (n P)^2 = 4.
  ExpectVec(v.mean_variance, glm::dvec3(0.5, 0.5, 0.0), "image mean");
}

TEST(PixelVariance, RejectsAGroupListOfAnotherLength) {
  const RecordBatch batch = TwoPixels(
      {Vertex(0, 0, 1.0f, 1.0f), Vertex(0, 1, 3.0f, 1.0f), Vertex(1, 0, 5.0f, 2.0f), Vertex(1, 1, 1.0f, 1.0f)});
  EXPECT_THROW(EstimatePixelVariance(batch, std::vector<std::uint32_t>{0, 0}, 1), std::invalid_argument);
}

// `hpsf render --backend emulated --variance` groups records by table slot: on a roomy table (no probe failure,
// no alias) the slots hold exactly the reference's cells, so the estimate is the reference's up to the order of
// the sums.
TEST(PixelVariance, TableSlotsGiveTheReferencesCellsVariance) {
  const RecordBatch batch = Trace(LoadScene("cornell"), 5);
  FilterConfig config;
  config.capacity = 1u << 16;
  const FilterResult reference = ReferenceFilter(batch, config);
  const EmulatedRun emulated = EmulatedFilter(batch, config, EmulatorOptions{});
  ASSERT_EQ(emulated.probe_failures, 0u);
  const PixelVariance a = EstimatePixelVariance(batch, reference.placement, reference.cells.size());
  const PixelVariance b = EstimatePixelVariance(batch, emulated.placements, emulated.table.capacity);
  for (std::size_t p = 0; p < a.variance.pixels.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(b.variance.pixels[p][c], a.variance.pixels[p][c], 1e-6 * a.variance.pixels[p][c]) << p;
    }
  }
  ExpectVec(b.mean_variance, a.mean_variance, "image mean");
}

}  // namespace
}  // namespace hpsf::testing
