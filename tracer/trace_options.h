// What the path tracer (tracer/path_tracer.h) is asked to trace: the image, samples, seed and frame, the depth of its
// paths and which of their vertices are filtered; checked without tracing, so that the option layer can refuse a bad
// value before any work (and a fuzz target can reach the check without Embree).
#ifndef HPSF_TRACER_TRACE_OPTIONS_H
#define HPSF_TRACER_TRACE_OPTIONS_H

#include <cstdint>

namespace hpsf {

inline constexpr std::uint32_t kMaxFilteredVertices = 8;  // TraceOptions::filtered_vertices

struct TraceOptions {
  std::uint32_t width = 256;
  std::uint32_t height = 256;
  std::uint32_t samples_per_pixel = 4;
  std::uint32_t seed = 1;
  std::uint32_t frame = 0;  // in the counter RNG, and the time at which an animated scene is traced
  // Surface vertices per path, the series truncated after the last one's emission; -1: unbounded, ended by
  // Russian roulette.
  int max_depth = 8;
  std::uint32_t filter_bounce = 0;  // which diffuse vertex becomes the filter vertex; 0 is the primary hit
  // Several filtered bounces (core/transport.h): each path also records the vertex it scatters to from its filter
  // vertex (RecordBatch::scattered) and ends there, so the record holds the light of one vertex further (that
  // vertex's emission, no next-event estimate from it, as --max-depth truncates) and the transport takes what lies
  // beyond from the table.
  bool scattered = false;
  // With scattered: the vertices of each path filtered, the first at filter_bounce; the others are the batch's deeper
  // records (RecordBatch::deeper), each also with the vertex it scattered to. The path ends at the last one's.
  std::uint32_t filtered_vertices = 1;
  // Amortized (A-nHPSF, tracer/path_continuation.h), with scattered: 0 off; else each sample also extends the path it
  // kept from the frame before by one vertex, filtered as one more deeper record per sample, while that vertex's index
  // stays below this depth (Meijer's precedence rule: the deepest path still below it is kept).
  std::uint32_t continuation_depth = 0;
  int threads = 0;  // 0: all cores

  void Validate() const;  // ConfigError naming the option
};

}  // namespace hpsf

#endif  // HPSF_TRACER_TRACE_OPTIONS_H
