#include "tools/hpsf/bounce_options.h"

#include <string>
#include <tuple>

#include "core/error.h"
#include "core/path_graph.h"
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

void AddAdaptiveTraceOptions(CLI::App& command, FilterConfig& config) {
  command
      .add_option_function<std::string>(
          "--survival", [&config](const std::string& text) { config.survival = ParseSurvival(text); },
          "Variance-aware path survival (Schipek eqs. 4.1, 4.2): off, linear:V0:V1[:FLOOR] or smooth:V0:V1[:FLOOR]. "
          "From a sequence's second frame on, each path survives its primary vertex with a probability p of its "
          "cell's variance in the table before the frame (at least FLOOR, default 0.0625), its light divided by p; a "
          "culled path is not traced on and adds 0. Needs --second-moments on")
      ->default_str("off");
  command
      .add_option_function<std::string>(
          "--path-graph", [&config](const std::string& text) { config.path_graph = ParsePathGraph(text); },
          "Adaptive path graphs (Schipek §4.2, eq. 4.7): off or a variance bound >= 0. From a sequence's second "
          "frame on, each path gathers the variance of its vertices' cells in the table before the frame (times "
          "its squared throughput) and is cut where the sum would pass the bound: the cell's average takes 1 - "
          "alpha of the rest of the path, the path traced on alpha, so the sum meets the bound. 0: every path "
          "takes its filter vertex's cell. Needs --second-moments on")
      ->default_str("off");
}

void CheckAdaptiveTrace(const FilterConfig& config, const TraceOptions& trace) {
  for (const auto& [on, option, what] :
       {std::tuple{config.survival.enabled(), "--survival", "decides at a path's primary vertex"},
        std::tuple{config.path_graph.enabled, "--path-graph", "gives a pixel's own light from its filter vertex on"}}) {
    if (!on) continue;
    if (trace.filter_bounce != 0) {
      throw ConfigError(option, std::string(what) + ", which needs --filter-bounce 0");
    }
    if (trace.scattered) {
      throw ConfigError(
          option, std::string(what) + "; it is not built with several filtered vertices, kept paths or the transport");
    }
  }
}

}  // namespace hpsf
