// What the baselines beside hashed filtering (plain path tracing, radius-search and screen-space path space
// filtering) know of each record: whether it is a filter vertex they may average over, its position, the radius
// it searches (HPSF's cell edge at its level, so that a baseline at radius scale 1 filters at HPSF's resolution),
// and its normal word (core/shared/key.h's normal test: two vertices are neighbours only with the same word).
// The level and normal word come from core's key with the jitter off, so they are the exact key path's.
#ifndef HPSF_REFERENCE_FILTER_VERTICES_H
#define HPSF_REFERENCE_FILTER_VERTICES_H

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/filter_config.h"
#include "core/image.h"
#include "core/record.h"

namespace hpsf {

struct FilterVertex {
  bool filtered = false;  // accepted, with a vertex, keyable: it averages and is averaged
  glm::dvec3 position{0.0};
  double radius = 0.0;
  std::uint32_t normal_word = 0;
};

// One per record of the batch. radius_scale multiplies each vertex's cell edge.
std::vector<FilterVertex> FilterVertices(const RecordBatch& batch, const FilterConfig& config, double radius_scale);

// Whether vertex j is a neighbour of vertex i: both filtered, the same normal word, |x_j - x_i| <= r_i (squared
// distance in double, summed over x, y, z in that order).
bool IsNeighbour(const FilterVertex& i, const FilterVertex& j);
double SquaredDistance(const glm::dvec3& a, const glm::dvec3& b);

struct NeighbourFilterResult {
  Image image;
  std::uint64_t filtered_records = 0;  // records that averaged over their neighbours
  double mean_neighbours = 0.0;        // per filtered record, itself included
  std::uint64_t max_neighbours = 0;
};

// What each record found: the mean of its neighbours' contributions and how many they were (0: none, the record
// keeps its own contribution). Filled per record, so no neighbour list outlives its record: a radius of a few cells
// at 64 spp finds thousands of neighbours per record, too many to keep for a million records.
struct NeighbourMeans {
  std::vector<std::optional<glm::dvec3>> means;
  std::vector<std::uint32_t> counts;
  explicit NeighbourMeans(std::size_t records) : means(records), counts(records, 0) {}
  // Record i's neighbours, ascending record indices, itself included: their contributions summed in that order,
  // so that no bit depends on threads.
  void Set(const RecordBatch& batch, std::size_t i, std::span<const std::uint32_t> neighbours);
};

// The image from the means, resolved as every backend resolves (core/resolve.h), with the neighbour counts.
NeighbourFilterResult ResolveNeighbourMeans(const RecordBatch& batch, const NeighbourMeans& means);

}  // namespace hpsf

#endif  // HPSF_REFERENCE_FILTER_VERTICES_H
