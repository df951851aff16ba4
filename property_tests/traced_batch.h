// A small traced batch of a built-in scene, as the property tests feed the backends: default tracer options but
// the size and samples per pixel.
#ifndef HPSF_PROPERTY_TESTS_TRACED_BATCH_H
#define HPSF_PROPERTY_TESTS_TRACED_BATCH_H

#include <cstdint>
#include <string>

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

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_TRACED_BATCH_H
