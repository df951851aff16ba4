// Distinct keys on purpose, for the statistics tests: one record per cell of a unit grid, no jitter, no level
// of detail, no normal bucket, so every record is its own key and tables differ only by a translation.
#ifndef HPSF_PROPERTY_TESTS_GRID_BATCH_H
#define HPSF_PROPERTY_TESTS_GRID_BATCH_H

#include <cstdint>

#include "core/filter_config.h"
#include "core/record.h"

namespace hpsf::testing {

// Unit cells, a table of `slots` slots, and a probe limit of the whole table unless given.
inline FilterConfig GridConfig(std::uint32_t slots, std::uint32_t probe_limit = 0) {
  FilterConfig config;
  config.lod = false;
  config.cell_size = 1.0f;
  config.jitter_scale = 0.0f;
  config.normal.mode = NormalMode::kNone;
  config.capacity = slots;
  config.probe_limit = probe_limit == 0 ? slots : probe_limit;
  return config;
}

// `count` records in distinct cells of a 64 x 64 x n grid translated by 4096 t along x: table t's keys.
inline RecordBatch GridBatch(int table, std::uint32_t count) {
  RecordBatch batch;
  batch.width = count;
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 1.0;
  for (std::uint32_t j = 0; j < count; ++j) {
    VertexSample v;
    v.pixel = j;
    v.position = glm::vec3(float(j % 64 + 4096u * std::uint32_t(table)), float((j / 64) % 64), float(j / 4096)) + 0.5f;
    v.previous = v.position + glm::vec3(0.0f, 0.0f, -1.0f);
    v.contribution = v.throughput = glm::vec3(0.5f);
    batch.records.push_back(MakeVertexRecord(v));
  }
  return batch;
}

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_GRID_BATCH_H
