#include "tracer/trace_options.h"

#include <string>

#include "core/error.h"

namespace hpsf {

void TraceOptions::Validate() const {
  if (width == 0 || height == 0 || width > 16384 || height > 16384) {
    throw ConfigError("--size", "width and height must lie in [1, 16384]; got " + std::to_string(width) + "x" +
                                    std::to_string(height));
  }
  if (samples_per_pixel == 0 || samples_per_pixel > 65536) {
    throw ConfigError("--spp", "must lie in [1, 65536]; got " + std::to_string(samples_per_pixel));
  }
  if (std::uint64_t(width) * height * samples_per_pixel > (1ull << 31)) {
    throw ConfigError("--spp", "width x height x spp must stay below 2^31 records");
  }
  if (max_depth < -1 || max_depth > 1024)
    throw ConfigError("--max-depth", "must be -1 (unbounded) or lie in [0, 1024]");
  if (threads < 0) throw ConfigError("--threads", "must be >= 0 (0: all cores)");
  if (filtered_vertices < 1 || filtered_vertices > kMaxFilteredVertices) {
    throw ConfigError("--filtered-vertices", "must lie in [1, " + std::to_string(kMaxFilteredVertices) + "]; got " +
                                                 std::to_string(filtered_vertices));
  }
  if (filtered_vertices > 1 && !scattered) {
    throw ConfigError("--filtered-vertices", "more than one filtered vertex needs the transport's scattered vertices");
  }
  if (continuation_depth > 0 && !scattered) {
    throw ConfigError("--continuation-depth",
                      "continuing paths across frames needs the transport's scattered vertices");
  }
  if (continuation_depth > 1024 ||
      (continuation_depth > 0 && continuation_depth <= filter_bounce + filtered_vertices)) {
    throw ConfigError("--continuation-depth",
                      "must be 0 (off) or lie in [" + std::to_string(filter_bounce + filtered_vertices + 1) +
                          ", 1024]: deeper than the vertex a frame's own path reaches (the filter bounce plus the "
                          "filtered vertices); got " +
                          std::to_string(continuation_depth));
  }
}

}  // namespace hpsf
