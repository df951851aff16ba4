#include "reference/screen_space_filter.h"

#include <algorithm>
#include <stdexcept>

#include "core/parallel_for.h"
#include "core/resolve.h"

namespace hpsf {

NeighbourFilterResult ScreenSpaceFilter(const RecordBatch& batch, const FilterConfig& config, double radius_scale,
                                        int window_radius_px) {
  CheckBatchShape(batch);
  config.Validate();
  if (window_radius_px < 0) throw std::invalid_argument("ScreenSpaceFilter: a negative window radius");
  const std::vector<FilterVertex> vertices = FilterVertices(batch, config, radius_scale);
  // Records are stored pixel by pixel, each pixel's samples together (core/record.h).
  const std::size_t spp = batch.samples_per_pixel;
  const int width = int(batch.width), height = int(batch.height);
  NeighbourMeans means(batch.records.size());
  ParallelFor(batch.records.size(), 1024, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> mine;
    for (std::size_t i = begin; i < end; ++i) {
      if (!vertices[i].filtered) continue;
      const int pixel = int(i / spp);
      const int px = pixel % width, py = pixel / width;
      mine.clear();
      for (int y = std::max(0, py - window_radius_px); y <= std::min(height - 1, py + window_radius_px); ++y) {
        for (int x = std::max(0, px - window_radius_px); x <= std::min(width - 1, px + window_radius_px); ++x) {
          const std::size_t first = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * spp;
          for (std::size_t j = first; j < first + spp; ++j) {
            if (IsNeighbour(vertices[i], vertices[j])) mine.push_back(std::uint32_t(j));
          }
        }
      }
      means.Set(batch, i, mine);  // rows, then columns, then samples: ascending record indices
    }
  });
  return ResolveNeighbourMeans(batch, means);
}

}  // namespace hpsf
