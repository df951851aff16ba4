// The occupancy of a HashCache's octree (Roth et al. §3.1; the cell test is core/shared/occupancy.h): which cells of
// each level the scene's triangles meet, as the bit fields a construction counts and builds its hash maps from. This
// is the reference's: every triangle tests every cell of its bounding box, one after another, as Roth describes.
#ifndef HPSF_CORE_OCCUPANCY_H
#define HPSF_CORE_OCCUPANCY_H

#include <array>
#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/shared/occupancy.h"

namespace hpsf {

using OccupancyTriangle = std::array<glm::vec3, 3>;

// The grid of 2^resolution_log2 finest cells per axis over the triangles' bounding box, with the smallest finest cell
// (a power of two) whose grid holds it; its origin is the box's first cell. An InputError naming `where` for no
// triangle, a vertex that is not finite, a resolution outside [2, 10], or a scene so far from the world's origin
// for its cell size that a cell index passes 2^31.
shared::OccupancyGrid GridOver(std::span<const OccupancyTriangle> triangles, int resolution_log2,
                               const std::string& where);

// One level's bit field: 2^(L - level) cells per axis (L the grid's resolution_log2), in blocks of 4 x 4 x 2 cells a
// word (a level of fewer than 4 cells per axis uses the corner of a 4 x 4 x 4 field).
class OccupancyLevel {
 public:
  OccupancyLevel(const shared::OccupancyGrid& grid, int level);  // every cell empty
  // A field read back from a device: `words` must have the level's count (a std::logic_error otherwise).
  OccupancyLevel(const shared::OccupancyGrid& grid, int level, std::vector<std::uint32_t> words);

  const shared::OccupancyGrid& grid() const { return grid_; }
  int level() const { return level_; }
  int cells_per_axis() const { return 1 << (grid_.resolution_log2 - level_); }
  bool Occupied(int x, int y, int z) const;
  void Mark(int x, int y, int z);
  std::uint64_t Count() const;  // the occupied cells: the words' popcounts summed
  const std::vector<std::uint32_t>& words() const { return words_; }
  // The occupied cells, word by word and bit by bit (a field is mostly empty): cell(x, y, z) for each.
  template <typename Cell>
  void ForEachOccupied(Cell cell) const {
    const int blocks_log2 = field_log2_ - 2;
    const std::uint32_t block_mask = (1u << blocks_log2) - 1u;
    for (std::uint32_t w = 0; w < words_.size(); ++w) {
      for (std::uint32_t bits = words_[w]; bits != 0u; bits &= bits - 1u) {
        const int bit = std::countr_zero(bits);
        cell(int(w & block_mask) * 4 + (bit & 3), int((w >> blocks_log2) & block_mask) * 4 + ((bit >> 2) & 3),
             int(w >> (2 * blocks_log2)) * 2 + (bit >> 4));
      }
    }
  }
  bool operator==(const OccupancyLevel& other) const;  // the same grid, level and cells

 private:
  shared::OccupancyGrid grid_;
  int level_;
  int field_log2_;  // the field's cells per axis, log 2: at least 2
  std::vector<std::uint32_t> words_;
};

// Every cell of `level` that one of the triangles meets (each triangle's vertices rounded by shared::FixedVertex), by
// testing every cell of each triangle's bounding box.
OccupancyLevel VoxelizeTriangles(const shared::OccupancyGrid& grid, std::span<const OccupancyTriangle> triangles,
                                 int level = 0);

// The level above `finer`: a cell is occupied when one of its 8 children is. Boxes are closed, so a triangle meets a
// cell exactly when it meets one of its children: the same field as voxelizing at that level.
OccupancyLevel Coarsened(const OccupancyLevel& finer);

// Every level from the finest (0) to the root (L), the finest voxelized and the rest coarsened.
std::vector<OccupancyLevel> OccupancyPyramid(const shared::OccupancyGrid& grid,
                                             std::span<const OccupancyTriangle> triangles);

}  // namespace hpsf

#endif  // HPSF_CORE_OCCUPANCY_H
