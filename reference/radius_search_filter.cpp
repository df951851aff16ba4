#include "reference/radius_search_filter.h"

#include <algorithm>
#include <cmath>

#include <nanoflann.hpp>

#include "core/parallel_for.h"
#include "core/resolve.h"

namespace hpsf {
namespace {

// nanoflann's view of the filtered vertices' positions.
struct VertexCloud {
  const std::vector<FilterVertex>* vertices;
  const std::vector<std::uint32_t>* indices;  // the filtered records
  std::size_t kdtree_get_point_count() const { return indices->size(); }
  double kdtree_get_pt(std::size_t k, std::size_t dim) const { return (*vertices)[(*indices)[k]].position[int(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, VertexCloud, double>, VertexCloud,
                                                 3, std::uint32_t>;

}  // namespace

NeighbourFilterResult RadiusSearchFilter(const RecordBatch& batch, const FilterConfig& config, double radius_scale) {
  CheckBatchShape(batch);
  config.Validate();
  const std::vector<FilterVertex> vertices = FilterVertices(batch, config, radius_scale);
  std::vector<std::uint32_t> filtered;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (vertices[i].filtered) filtered.push_back(std::uint32_t(i));
  }
  NeighbourMeans means(batch.records.size());
  if (!filtered.empty()) {
    const VertexCloud cloud{&vertices, &filtered};
    Tree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    tree.buildIndex();
    ParallelFor(filtered.size(), 256, [&](std::size_t begin, std::size_t end) {
      std::vector<std::pair<std::uint32_t, double>> found;
      std::vector<std::uint32_t> mine;
      for (std::size_t k = begin; k < end; ++k) {
        const FilterVertex& v = vertices[filtered[k]];
        const double query[3] = {v.position.x, v.position.y, v.position.z};
        // The tree keeps distances strictly below its bound; a bound a little above r^2 proposes every vertex the
        // exact test may keep.
        const double bound = std::nextafter(v.radius * v.radius * (1.0 + 1e-9), HUGE_VAL);
        found.clear();
        tree.radiusSearch(query, bound, found, nanoflann::SearchParams(32, 0.0f, false));
        mine.clear();
        for (const auto& [index, distance] : found) {
          const std::uint32_t j = filtered[index];
          if (IsNeighbour(v, vertices[j])) mine.push_back(j);
        }
        std::sort(mine.begin(), mine.end());
        means.Set(batch, filtered[k], mine);
      }
    });
  }
  return ResolveNeighbourMeans(batch, means);
}

}  // namespace hpsf
