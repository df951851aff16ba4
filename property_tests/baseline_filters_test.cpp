// The baselines beside hashed filtering (reference/radius_search_filter.h, reference/screen_space_filter.h): the
// k-d tree finds exactly the neighbours a brute-force search over every pair finds, for level of detail on and off
// and every normal test, so the images are bit-identical; the neighbour test itself on constructed vertices; a
// radius too small to reach another vertex is plain path tracing, bit for bit; a window that covers the image makes
// the screen-space filter the radius search, and a window of one pixel at 1 spp plain path tracing.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/filter_config.h"
#include "property_tests/traced_batch.h"
#include "reference/filter_vertices.h"
#include "reference/radius_search_filter.h"
#include "reference/reference_filter.h"
#include "reference/screen_space_filter.h"

namespace hpsf {
namespace {

NeighbourFilterResult BruteForce(const RecordBatch& batch, const FilterConfig& config, double radius_scale) {
  const std::vector<FilterVertex> v = FilterVertices(batch, config, radius_scale);
  NeighbourMeans means(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    std::vector<std::uint32_t> neighbours;
    for (std::size_t j = 0; j < v.size(); ++j) {
      if (IsNeighbour(v[i], v[j])) neighbours.push_back(std::uint32_t(j));
    }
    means.Set(batch, i, neighbours);
  }
  return ResolveNeighbourMeans(batch, means);
}

struct Case {
  const char* name;
  bool lod;
  const char* normal;
  double radius_scale;
};

TEST(RadiusSearch, FindsWhatTheBruteForceFinds) {
  const RecordBatch batch = testing::TracedBatch("cornell", 24, 2);
  for (const Case c :
       {Case{"lod, sign", true, "sign", 1.0}, Case{"lod, none, 3 cells", true, "none", 3.0},
        Case{"lod, octahedral:2", true, "octahedral:2", 2.0}, Case{"fixed cells of 16, sign", false, "sign", 1.0}}) {
    SCOPED_TRACE(c.name);
    FilterConfig config;
    config.lod = c.lod;
    config.cell_size = 16.0f;
    config.normal = ParseNormalKey(c.normal);
    const NeighbourFilterResult tree = RadiusSearchFilter(batch, config, c.radius_scale);
    const NeighbourFilterResult brute = BruteForce(batch, config, c.radius_scale);
    EXPECT_EQ(tree.filtered_records, brute.filtered_records);
    EXPECT_EQ(tree.max_neighbours, brute.max_neighbours);
    EXPECT_EQ(tree.mean_neighbours, brute.mean_neighbours);
    EXPECT_GT(tree.mean_neighbours, 1.5) << "the case must average over more than the vertex itself";
    EXPECT_TRUE(SameBits(tree.image, brute.image));
  }
}

TEST(RadiusSearch, TheNeighbourTestHoldsAtItsBoundaries) {
  FilterVertex a{true, {1.0, 2.0, 3.0}, 0.5, 7};
  FilterVertex b = a;
  b.position.x += 0.5;  // exactly r away: a neighbour
  EXPECT_TRUE(IsNeighbour(a, b));
  b.position.x = std::nextafter(b.position.x, 10.0);
  EXPECT_FALSE(IsNeighbour(a, b));
  b = a;
  b.normal_word = 8;
  EXPECT_FALSE(IsNeighbour(a, b));
  b = a;
  b.filtered = false;
  EXPECT_FALSE(IsNeighbour(a, b));
  EXPECT_FALSE(IsNeighbour(b, a));
  b = a;
  b.radius = 0.0;  // the radius is the searching vertex's: a finds b, b finds only itself
  b.position.y += 0.25;
  EXPECT_TRUE(IsNeighbour(a, b));
  EXPECT_FALSE(IsNeighbour(b, a));
}

TEST(RadiusSearch, ARadiusThatReachesNoOtherVertexIsPlainPathTracing) {
  const RecordBatch batch = testing::TracedBatch("cornell", 24, 2);
  const NeighbourFilterResult tiny = RadiusSearchFilter(batch, FilterConfig{}, 1e-12);
  EXPECT_EQ(tiny.max_neighbours, 1u);
  EXPECT_TRUE(SameBits(tiny.image, UnfilteredImage(batch)));
}

TEST(ScreenSpace, AWindowOverTheWholeImageIsTheRadiusSearch) {
  const RecordBatch batch = testing::TracedBatch("cornell", 16, 2);
  const FilterConfig config;
  const NeighbourFilterResult screen = ScreenSpaceFilter(batch, config, 1.0, 16);
  const NeighbourFilterResult radius = RadiusSearchFilter(batch, config, 1.0);
  EXPECT_EQ(screen.mean_neighbours, radius.mean_neighbours);
  EXPECT_TRUE(SameBits(screen.image, radius.image));
  // With a radius of four cell edges (16 pixels of footprint), the default 9x9 window misses what lies outside it.
  EXPECT_LT(ScreenSpaceFilter(batch, config, 4.0).mean_neighbours,
            RadiusSearchFilter(batch, config, 4.0).mean_neighbours);
}

TEST(ScreenSpace, AOnePixelWindowAtOneSampleIsPlainPathTracing) {
  const RecordBatch batch = testing::TracedBatch("cornell", 16, 1);
  EXPECT_TRUE(SameBits(ScreenSpaceFilter(batch, FilterConfig{}, 1.0, 0).image, UnfilteredImage(batch)));
}

}  // namespace
}  // namespace hpsf
