#include "core/occupancy.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/error.h"

namespace hpsf {
namespace {

// floor(x * 2^-c), exact in double (a float times a power of two).
double CellCoordinate(float x, int c) { return std::floor(std::ldexp(double(x), -c)); }

}  // namespace

shared::OccupancyGrid GridOver(std::span<const OccupancyTriangle> triangles, int resolution_log2,
                               const std::string& where) {
  if (resolution_log2 < shared::kMinOccupancyResolutionLog2 || resolution_log2 > shared::kMaxOccupancyResolutionLog2) {
    throw InputError(where + ": the occupancy grid's resolution must be 2^2 to 2^10 cells per axis; got 2^" +
                     std::to_string(resolution_log2));
  }
  if (triangles.empty()) throw InputError(where + ": no triangle to build an occupancy grid over");
  glm::vec3 low(std::numeric_limits<float>::max()), high(std::numeric_limits<float>::lowest());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const glm::vec3& v : triangles[t]) {
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
        throw InputError(where + ": triangle " + std::to_string(t) + " has a vertex that is not finite");
      }
      low = glm::min(low, v);
      high = glm::max(high, v);
    }
  }
  // The smallest power of two whose grid of 2^L cells from the box's first cell reaches its last.
  const double extent = std::max({double(high.x) - low.x, double(high.y) - low.y, double(high.z) - low.z});
  int c = extent > 0.0 ? std::ilogb(extent) - resolution_log2 : -126;
  c = std::max(c, -126);
  const auto fits = [&](int exponent) {
    for (int a = 0; a < 3; ++a) {
      if (CellCoordinate(high[a], exponent) - CellCoordinate(low[a], exponent) >= std::ldexp(1.0, resolution_log2))
        return false;
    }
    return true;
  };
  while (!fits(c)) ++c;
  for (int a = 0; a < 3; ++a) {
    const double limit = std::ldexp(1.0, 31) - std::ldexp(1.0, resolution_log2);
    if (std::abs(CellCoordinate(low[a], c)) >= limit || std::abs(CellCoordinate(high[a], c)) >= limit) {
      throw InputError(where + ": the scene lies too far from the world's origin for its occupancy cell of 2^" +
                       std::to_string(c) + " (a cell index passes 2^31)");
    }
  }
  shared::OccupancyGrid grid;
  grid.cell_exponent = c;
  grid.origin_x = int(CellCoordinate(low.x, c));
  grid.origin_y = int(CellCoordinate(low.y, c));
  grid.origin_z = int(CellCoordinate(low.z, c));
  grid.resolution_log2 = resolution_log2;
  return grid;
}

OccupancyLevel::OccupancyLevel(const shared::OccupancyGrid& grid, int level)
    : grid_(grid),
      level_(level),
      field_log2_(shared::OccupancyFieldLog2(grid.resolution_log2, level)),
      words_(shared::OccupancyWords(field_log2_), 0u) {}

OccupancyLevel::OccupancyLevel(const shared::OccupancyGrid& grid, int level, std::vector<std::uint32_t> words)
    : OccupancyLevel(grid, level) {
  if (words.size() != words_.size()) throw std::logic_error("an occupancy field of the wrong size");
  words_ = std::move(words);
}

bool OccupancyLevel::Occupied(int x, int y, int z) const {
  return (words_[shared::OccupancyWord(x, y, z, field_log2_)] >> shared::OccupancyBit(x, y, z)) & 1u;
}

void OccupancyLevel::Mark(int x, int y, int z) {
  words_[shared::OccupancyWord(x, y, z, field_log2_)] |= 1u << shared::OccupancyBit(x, y, z);
}

std::uint64_t OccupancyLevel::Count() const {
  std::uint64_t count = 0;
  for (const std::uint32_t word : words_) count += std::popcount(word);
  return count;
}

bool OccupancyLevel::operator==(const OccupancyLevel& other) const {
  const shared::OccupancyGrid& a = grid_;
  const shared::OccupancyGrid& b = other.grid_;
  return a.cell_exponent == b.cell_exponent && a.origin_x == b.origin_x && a.origin_y == b.origin_y &&
         a.origin_z == b.origin_z && a.resolution_log2 == b.resolution_log2 && level_ == other.level_ &&
         words_ == other.words_;
}

OccupancyLevel VoxelizeTriangles(const shared::OccupancyGrid& grid, std::span<const OccupancyTriangle> triangles,
                                 int level) {
  OccupancyLevel field(grid, level);
  for (const OccupancyTriangle& t : triangles) {
    const shared::FixedPoint3 v0 = shared::FixedVertex(grid, t[0]);
    const shared::FixedPoint3 v1 = shared::FixedVertex(grid, t[1]);
    const shared::FixedPoint3 v2 = shared::FixedVertex(grid, t[2]);
    const shared::CellRange r = shared::TriangleCellRange(v0, v1, v2, level, grid.resolution_log2);
    for (int z = r.z0; z <= r.z1; ++z) {
      for (int y = r.y0; y <= r.y1; ++y) {
        for (int x = r.x0; x <= r.x1; ++x) {
          if (shared::TriangleMeetsCell(v0, v1, v2, x, y, z, level)) field.Mark(x, y, z);
        }
      }
    }
  }
  return field;
}

OccupancyLevel Coarsened(const OccupancyLevel& finer) {
  OccupancyLevel coarse(finer.grid(), finer.level() + 1);
  finer.ForEachOccupied([&](int x, int y, int z) { coarse.Mark(x >> 1, y >> 1, z >> 1); });
  return coarse;
}

std::vector<OccupancyLevel> OccupancyPyramid(const shared::OccupancyGrid& grid,
                                             std::span<const OccupancyTriangle> triangles) {
  std::vector<OccupancyLevel> levels = {VoxelizeTriangles(grid, triangles)};
  while (levels.back().level() < grid.resolution_log2) levels.push_back(Coarsened(levels.back()));
  return levels;
}

}  // namespace hpsf
