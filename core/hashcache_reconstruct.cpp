#include "core/hashcache_reconstruct.h"

#include <algorithm>
#include <optional>

namespace hpsf {
namespace {

// The average light of a cell's side, or none where no sample reached it.
std::optional<glm::dvec3> SideAverage(const HashCache& cache, const HashCacheLevel& level, std::uint32_t slot,
                                      std::size_t side) {
  const std::uint64_t count = level.data.counts[2 * slot + side];
  if (count == 0) return std::nullopt;
  glm::dvec3 sum;
  for (int c = 0; c < 3; ++c) {
    const std::size_t at = 6 * std::size_t(slot) + 3 * side + c;
    sum[c] = cache.accumulation == Accumulation::kFixed64
                 ? IntegerSumValue(level.data.fixed_sums[at], Accumulation::kFixed64, cache.fixed_point_bits)
                 : double(level.data.float_sums[at]);
  }
  return sum / double(count);
}

}  // namespace

HashCacheReconstruction ReconstructHashCache(const HashCache& cache, const RecordBatch& primary,
                                             const shared::HashCacheLookupParams& params) {
  HashCacheReconstruction result;
  result.image = Image(primary.width, primary.height);
  result.per_level.assign(cache.levels.size(), 0);
  const std::size_t pixels = std::size_t(primary.width) * primary.height;
  const std::uint32_t spp = primary.samples_per_pixel;
  // Per sample: the light its lookup found, if any. Per pixel: the sum and count of its valid samples' light.
  std::vector<std::optional<glm::dvec3>> found(primary.records.size());
  std::vector<glm::dvec3> pixel_light(pixels, glm::dvec3(0.0));
  std::vector<std::uint32_t> pixel_valid(pixels, 0);
  for (std::size_t i = 0; i < primary.records.size(); ++i) {
    const Record& r = primary.records[i];
    if (!RecordHasVertex(r)) continue;
    ++result.lookups;
    const int level = shared::HashCacheLevelOf(params, r);
    ++result.per_level[std::size_t(level)];
    const std::uint32_t key = shared::HashCacheLookupKey(params, r, level);
    if (key == shared::kCuckooEmpty) {
      ++result.off_grid;
      continue;
    }
    const HashCacheLevel& at = cache.levels[std::size_t(level)];
    const std::optional<std::uint32_t> slot = at.map.Find(key);
    if (!slot) {
      ++result.invalid;
      continue;
    }
    const std::uint32_t front = at.data.front[*slot];
    const std::size_t side =
        front == shared::kFrontUnclaimed || shared::FacesFront(shared::FrontWord(r.path.w), front) ? 0 : 1;
    found[i] = SideAverage(cache, at, *slot, side);
    if (!found[i]) {
      ++result.unsampled;
      continue;
    }
    pixel_light[r.path.x] += *found[i];
    ++pixel_valid[r.path.x];
  }
  std::vector<glm::dvec3> pixel_radiance(pixels, glm::dvec3(0.0));
  for (std::size_t i = 0; i < primary.records.size(); ++i) {
    const Record& r = primary.records[i];
    const std::uint32_t pixel = r.path.x;
    glm::dvec3 radiance(r.radiance_before);
    if (RecordHasVertex(r)) {
      glm::dvec3 light(0.0);
      if (found[i]) {
        light = *found[i];
      } else {
        const std::uint32_t x = pixel % primary.width, y = pixel / primary.width;
        glm::dvec3 sum(0.0);
        std::uint64_t valid = 0;
        for (std::uint32_t ny = y == 0 ? 0 : y - 1; ny <= std::min(y + 1, primary.height - 1); ++ny) {
          for (std::uint32_t nx = x == 0 ? 0 : x - 1; nx <= std::min(x + 1, primary.width - 1); ++nx) {
            sum += pixel_light[std::size_t(ny) * primary.width + nx];
            valid += pixel_valid[std::size_t(ny) * primary.width + nx];
          }
        }
        if (valid > 0) {
          light = sum / double(valid);
          ++result.filled;
        } else {
          ++result.unfilled;
        }
      }
      radiance += glm::dvec3(r.throughput) * light;
    }
    pixel_radiance[pixel] += radiance;
  }
  for (std::size_t p = 0; p < pixels; ++p) result.image.pixels[p] = glm::vec3(pixel_radiance[p] / double(spp));
  return result;
}

}  // namespace hpsf
