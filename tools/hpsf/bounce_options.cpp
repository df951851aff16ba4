#include "tools/hpsf/bounce_options.h"

#include <string>

#include "core/error.h"
#include "core/survival.h"

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

void AddSurvivalOption(CLI::App& command, FilterConfig& config) {
  command
      .add_option_function<std::string>(
          "--survival", [&config](const std::string& text) { config.survival = ParseSurvival(text); },
          "Variance-aware path survival (Schipek eqs. 4.1, 4.2): off, linear:V0:V1[:FLOOR] or smooth:V0:V1[:FLOOR]. "
          "From a sequence's second frame on, each path survives its primary vertex with a probability p of its "
          "cell's variance in the table before the frame (at least FLOOR, default 0.0625), its light divided by p; a "
          "culled path is not traced on and adds 0. Needs --second-moments on")
      ->default_str("off");
}

void CheckSurvival(const FilterConfig& config, const TraceOptions& trace) {
  if (!config.survival.enabled()) return;
  if (trace.filter_bounce != 0) {
    throw ConfigError("--survival", "decides at a path's primary vertex, which needs --filter-bounce 0");
  }
  if (trace.scattered) {
    throw ConfigError("--survival",
                      "decides at a path's primary vertex; it is not built with several filtered vertices, kept paths "
                      "or the transport");
  }
}

}  // namespace hpsf
