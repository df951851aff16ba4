// Small traced batches, as the property tests feed the backends: default tracer options but the size, the
// samples per pixel and the frame.
#ifndef HPSF_PROPERTY_TESTS_TRACED_BATCH_H
#define HPSF_PROPERTY_TESTS_TRACED_BATCH_H

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/record.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf::testing {

inline RecordBatch TracedBatch(const std::string& scene, std::uint32_t size, std::uint32_t spp) {
  TraceOptions trace;
  trace.width = trace.height = size;
  trace.samples_per_pixel = spp;
  return TraceRecords(LoadScene(scene), trace).batch;
}

// Frames 0 to frames - 1 of a scene: its keyframes, and the frame in every random number. filtered_vertices > 0:
// several filtered bounces (core/transport.h), that many vertices filtered per path, with the scattered vertices.
inline std::vector<RecordBatch> TracedFrames(const Scene& scene, std::uint32_t size, std::uint32_t spp,
                                             std::uint32_t frames, std::uint32_t filtered_vertices = 0) {
  std::vector<RecordBatch> batches;
  for (std::uint32_t frame = 0; frame < frames; ++frame) {
    TraceOptions trace;
    trace.width = trace.height = size;
    trace.samples_per_pixel = spp;
    trace.frame = frame;
    trace.scattered = filtered_vertices > 0;
    trace.filtered_vertices = std::max(filtered_vertices, 1u);
    batches.push_back(TraceRecords(scene, trace).batch);
  }
  return batches;
}

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_TRACED_BATCH_H
