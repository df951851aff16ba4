// The furnaces several filtered bounces are tested in (core/transport.h): a synthetic one whose every record's path
// scatters into another cell of a 2 x 2 x 2 block, and the traced one (scenes/furnace.json) with a chain of filtered
// vertices per path.
#ifndef HPSF_PROPERTY_TESTS_TRANSPORT_FURNACE_H
#define HPSF_PROPERTY_TESTS_TRANSPORT_FURNACE_H

#include <cstdint>
#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/record.h"
#include "core/temporal.h"
#include "property_tests/grid_batch.h"
#include "property_tests/traced_batch.h"
#include "tracer/scene_file.h"

namespace hpsf::testing {

inline const glm::vec3 kEmission(1.0f, 0.5f, 0.25f);  // e: what every path finds beyond its filter vertex
inline const glm::vec3 kAlbedo(0.5f, 0.75f, 0.25f);   // a: the transport weight to the scattered vertex
inline constexpr std::uint32_t kCells = 8;            // a 2 x 2 x 2 block of unit cells
inline constexpr std::uint32_t kPerCell = 8;

inline glm::vec3 CellCorner(std::uint32_t cell) {
  return glm::vec3(float(cell & 1u), float((cell >> 1) & 1u), float(cell >> 2));
}

// The cell record j of cell c scatters into: c + 1 + j mod (kCells - 1), so every cell is reached from every other.
inline std::uint32_t ScatteredCell(std::uint32_t c, std::uint32_t j) { return (c + 1 + j % (kCells - 1)) % kCells; }

// What cell c's records find beyond their filter vertex: e in the furnace, e (c + 1) / 8 where the light varies.
inline glm::vec3 EmissionOf(std::uint32_t c, bool varying) {
  return varying ? kEmission * float(c + 1) / 8.0f : kEmission;
}

// The synthetic furnace: kPerCell records in each of kCells cells, each record's path scattering into another cell.
// `varying`: each cell's records find another emission, so cells differ and a record must read the right one.
inline RecordBatch FurnaceBatch(std::uint32_t frame, bool varying = false) {
  RecordBatch batch;
  batch.width = kCells * kPerCell;
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 1.0;
  batch.frame = frame;
  for (std::uint32_t c = 0; c < kCells; ++c) {
    for (std::uint32_t j = 0; j < kPerCell; ++j) {
      VertexSample v;
      v.pixel = c * kPerCell + j;
      v.position = CellCorner(c) + glm::vec3(0.0625f + 0.125f * float(j), 0.5f, 0.25f);
      v.previous = v.position + glm::vec3(0.0f, 0.0f, -4.0f);
      v.contribution = EmissionOf(c, varying);
      v.throughput = glm::vec3(1.0f);
      batch.records.push_back(MakeVertexRecord(v));
      VertexSample s;
      s.pixel = v.pixel;
      s.bounce = 1;
      s.position = CellCorner(ScatteredCell(c, j)) + glm::vec3(0.5f, 0.125f + 0.0625f * float(j), 0.75f);
      s.previous = v.position;
      s.throughput = kAlbedo;
      batch.scattered.push_back(MakeVertexRecord(s));
    }
  }
  return batch;
}

inline FilterConfig FurnaceConfig(Accumulation accumulation, const std::string& temporal, std::uint32_t frames) {
  FilterConfig config = GridConfig(1u << 10, 16);
  config.accumulation = accumulation;
  config.temporal = ParseTemporal(temporal);
  config.frames = frames;
  config.transport = true;
  return config;
}

// The traced furnace's first `frames` frames at size x size pixels and `spp` samples, each path filtering `filtered`
// vertices and carrying its scattered vertices.
inline std::vector<RecordBatch> TracedFurnaceFrames(std::uint32_t filtered, std::uint32_t frames, std::uint32_t size,
                                                    std::uint32_t spp) {
  return TracedFrames(LoadScene(HPSF_SCENES_DIR "/furnace.json"), size, spp, frames, filtered);
}

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_TRANSPORT_FURNACE_H
