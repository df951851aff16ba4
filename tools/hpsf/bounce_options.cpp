#include "tools/hpsf/bounce_options.h"

namespace hpsf {

void AddBounceOptions(CLI::App& command, TraceOptions& trace) {
  command
      .add_option("--filtered-vertices", trace.filtered_vertices,
                  "Diffuse vertices filtered per path, from --filter-bounce on, 1..8: each further one a deeper "
                  "record in the table (several filtered bounces; the path then ends at the vertex the last one "
                  "scatters to)")
      ->capture_default_str();
  command
      .add_option("--continuation-depth", trace.continuation_depth,
                  "Amortized several filtered bounces (A-nHPSF): each sample also extends the path it kept from the "
                  "frame before by one filtered vertex, while the vertex's index stays below this depth; 0: off. Any "
                  "change of the scene or camera drops the kept paths")
      ->capture_default_str();
}

void TraceScatteredVertices(const FilterConfig& config, TraceOptions& trace) {
  trace.scattered = config.transport || trace.filtered_vertices > 1 || trace.continuation_depth > 0;
}

}  // namespace hpsf
