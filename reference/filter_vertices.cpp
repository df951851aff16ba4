#include "reference/filter_vertices.h"

#include <algorithm>

#include "core/footprint.h"
#include "core/input_check.h"
#include "core/resolve.h"
#include "core/shared/key.h"

namespace hpsf {

std::vector<FilterVertex> FilterVertices(const RecordBatch& batch, const FilterConfig& config, double radius_scale) {
  const float footprint = FootprintScale(config.filter_width_px, batch.fov_y_radians, batch.height);
  shared::KeyParams params = MakeKeyParams(config, footprint, static_cast<std::uint32_t>(batch.records.size()));
  params.jitter_scale = 0.0f;  // the vertex's own cell, not a jittered neighbour's
  std::vector<FilterVertex> vertices(batch.records.size());
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    const Record& r = batch.records[i];
    if (CheckRecordInputs(r) != InputVerdict::kAccepted || !shared::RecordHasVertex(r)) continue;
    const shared::KeyResult key = shared::ComputeKey(params, r);
    if (key.status != shared::kKeyed) continue;
    FilterVertex& v = vertices[i];
    v.filtered = true;
    v.position = glm::dvec3(r.position.x, r.position.y, r.position.z);
    const double edge = params.lod_enabled ? double(shared::PowerOfTwo(key.level)) : double(params.cell_size);
    v.radius = radius_scale * edge;
    v.normal_word = key.words.normal;
  }
  return vertices;
}

double SquaredDistance(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 d = b - a;
  return d.x * d.x + d.y * d.y + d.z * d.z;
}

bool IsNeighbour(const FilterVertex& i, const FilterVertex& j) {
  return i.filtered && j.filtered && i.normal_word == j.normal_word &&
         SquaredDistance(i.position, j.position) <= i.radius * i.radius;
}

void NeighbourMeans::Set(const RecordBatch& batch, std::size_t i, std::span<const std::uint32_t> neighbours) {
  counts[i] = std::uint32_t(neighbours.size());
  if (neighbours.empty()) return;
  glm::dvec3 sum(0.0);
  for (const std::uint32_t j : neighbours) {
    const auto& c = batch.records[j].contribution;
    sum += glm::dvec3(c.x, c.y, c.z);
  }
  means[i] = sum / double(neighbours.size());
}

NeighbourFilterResult ResolveNeighbourMeans(const RecordBatch& batch, const NeighbourMeans& means) {
  NeighbourFilterResult result;
  std::uint64_t total = 0;
  for (const std::uint32_t count : means.counts) {
    if (count == 0) continue;
    ++result.filtered_records;
    total += count;
    result.max_neighbours = std::max<std::uint64_t>(result.max_neighbours, count);
  }
  result.mean_neighbours = result.filtered_records ? double(total) / double(result.filtered_records) : 0.0;
  result.image = ResolvePixels(batch, means.means);
  return result;
}

}  // namespace hpsf
