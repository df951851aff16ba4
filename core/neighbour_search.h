// The resolve's neighbourhood search on the host (core/shared/neighbour_search.h holds the rule): which cells a
// record's resolve reads beside its chosen one, for the reference (its exact maps), the emulator's resolve and the
// checks of every hashed backend's image (a lookup in the table read back), and the average of what it read.
#ifndef HPSF_CORE_NEIGHBOUR_SEARCH_H
#define HPSF_CORE_NEIGHBOUR_SEARCH_H

#include <array>
#include <cstdint>
#include <functional>
#include <optional>

#include <glm/vec3.hpp>

#include "core/accumulation.h"
#include "core/key_batch.h"
#include "core/record.h"
#include "core/shared/levels.h"
#include "core/shared/neighbour_search.h"

namespace hpsf {

inline constexpr std::uint32_t kNotRead = 0xFFFFFFFFu;

// A record's search: the stencil's corners 1..7 around its chosen cell ([c - 1] for corner c), each the cell (or
// slot) the lookup found, or kNotRead.
struct NeighbourReads {
  std::uint32_t record = 0;
  std::uint32_t level = 0;  // the chosen level, k levels above the record's own cell
  std::array<std::uint32_t, shared::kStencilCells - 1> cells{};
};

// Finds the cell (or slot) holding these key words with samples, or nothing.
using CellFinder = std::function<std::optional<std::uint32_t>(const shared::KeyWords&)>;

// Whether record i's resolve searches: the search is on and its chosen cell holds fewer than min_count samples.
inline bool Searches(bool neighbour_search, const shared::LevelChoice& chosen, std::uint32_t not_placed) {
  return neighbour_search && chosen.slot < not_placed && chosen.settled == 0u;
}

// The key words of the stencil's corners 1..7 around a record's cell `level` levels above its own ([c - 1] for corner
// c), from its jittered position (core/shared/key.h's JitteredKeyPosition, computed once by the caller).
std::array<shared::KeyWords, shared::kStencilCells - 1> StencilNeighbourWords(const KeyParams& params, const Record& r,
                                                                              const shared::KeyPosition& at,
                                                                              std::uint32_t level);

// The stencil's corners around the record's chosen level, each looked up with `find`; its key and position are
// computed again (the jitter once).
NeighbourReads SearchNeighbours(const KeyParams& params, const Record& r, const shared::LevelChoice& chosen,
                                std::uint32_t record, const CellFinder& find);

// The sums and counts of the cells a resolve read, added: integers exactly, float32 sums in double in corner order.
struct StencilTotal {
  std::array<std::uint64_t, 3> fixed_sum{};
  glm::dvec3 float_sum{0.0};
  std::uint64_t count = 0;

  void Add(const std::array<std::uint64_t, 3>& fixed, const std::array<float, 3>& floating, std::uint64_t n);
  // Sums / count, per channel, as the resolve of one cell computes it: one cell read gives that cell's average.
  glm::dvec3 Average(Accumulation accumulation, int fixed_point_bits) const;
};

}  // namespace hpsf

#endif  // HPSF_CORE_NEIGHBOUR_SEARCH_H
