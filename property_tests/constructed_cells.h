// Inputs constructed by cell for the broken-kernel and broken-shader tests: level of detail off, unit cells, no
// jitter, no normal bucket, so a record at (x + 0.5, y + 0.5, z + 0.5) has the cell (x, y, z) and its slot0 and
// fingerprint are known before it is filtered. Cells are searched by a predicate on the key core computes, so
// the inputs reach their defect whatever the hashes and the key path become.
#ifndef HPSF_PROPERTY_TESTS_CONSTRUCTED_CELLS_H
#define HPSF_PROPERTY_TESTS_CONSTRUCTED_CELLS_H

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "core/filter_config.h"
#include "core/key_batch.h"
#include "core/record.h"
#include "core/shared/key.h"

namespace hpsf::testing {

inline FilterConfig ConstructedConfig(std::uint32_t capacity, std::uint32_t probe_limit,
                                      std::uint32_t fingerprint_bits = 32) {
  FilterConfig c;
  c.lod = false;
  c.cell_size = 1.0f;
  c.jitter_scale = 0.0f;
  c.normal = {NormalMode::kNone, 0};
  c.capacity = capacity;
  c.probe_limit = probe_limit;
  c.fingerprint_bits = fingerprint_bits;
  return c;
}

inline KeyResult KeyOfCell(const FilterConfig& config, glm::ivec3 cell) {
  VertexSample v;
  v.position = glm::vec3(cell) + glm::vec3(0.5f);
  v.previous = v.position + glm::vec3(0.0f, 0.0f, -10.0f);
  return shared::ComputeKey(MakeKeyParams(config, 0.01f, 1), MakeVertexRecord(v));
}

// One record per point, in this order (neighbours share a warp or a subgroup); contributions are multiples of 2^-3.
inline RecordBatch BatchAtPoints(const std::vector<glm::vec3>& points) {
  RecordBatch batch;
  batch.width = static_cast<std::uint32_t>(points.size());
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 0.5;
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    VertexSample v;
    v.pixel = i;
    v.position = points[i];
    v.previous = v.position + glm::vec3(0.0f, 0.0f, -10.0f);
    v.contribution = glm::vec3(1.0f + 0.25f * float(i % 7), 0.5f, 0.125f);
    v.throughput = glm::vec3(0.5f);
    batch.records.push_back(MakeVertexRecord(v));
  }
  return batch;
}

// One record at the centre of each cell, in this order.
inline RecordBatch BatchOfCells(const std::vector<glm::ivec3>& cells) {
  std::vector<glm::vec3> centres;
  for (const glm::ivec3& c : cells) centres.push_back(glm::vec3(c) + glm::vec3(0.5f));
  return BatchAtPoints(centres);
}

// The first cell along x (from `start`) whose key satisfies `wanted`.
inline glm::ivec3 FindCell(const FilterConfig& config, const std::function<bool(const KeyResult&)>& wanted,
                           int start = 0) {
  for (int x = start; x < start + 2000000; ++x) {
    if (wanted(KeyOfCell(config, {x, 3, -7}))) return {x, 3, -7};
  }
  ADD_FAILURE() << "no cell found";
  return {0, 0, 0};
}

// A key whose fingerprint, reduced to the config's width, is 0 before the fix that keeps it off the empty tag.
inline bool ReducesToZero(const FilterConfig& config, const KeyResult& k) {
  return (shared::FullFingerprint(k.words) >> (32u - config.fingerprint_bits)) == 0u;
}

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_CONSTRUCTED_CELLS_H
