// The trace options of sequences, the same on every command that traces them (render, crosscheck): how many vertices
// of a path are filtered and how deep a path is continued across frames, the rule that traces the scattered vertices
// the transport reads, and the tracer's reads of the table before the frame (path survival and path graphs). Apart from
// the tracer, so that fuzz_cli reaches them.
#ifndef HPSF_TOOLS_HPSF_BOUNCE_OPTIONS_H
#define HPSF_TOOLS_HPSF_BOUNCE_OPTIONS_H

#include <CLI/CLI.hpp>

#include "core/filter_config.h"
#include "tracer/trace_options.h"

namespace hpsf {

// --filtered-vertices and --continuation-depth, into `trace`.
void AddBounceOptions(CLI::App& command, TraceOptions& trace);

// A scene traced for several filtered bounces (core/transport.h): with its scattered vertices where the filter
// transports (--transport on), a path filters more than one vertex (--filtered-vertices) or continues across frames
// (--continuation-depth).
void TraceScatteredVertices(const FilterConfig& config, TraceOptions& trace);

// --survival (core/survival.h) and --path-graph (core/path_graph.h), into config.survival and config.path_graph.
void AddAdaptiveTraceOptions(CLI::App& command, FilterConfig& config);

// Survival and path graphs decide from a path's primary vertex on: a ConfigError naming the option where the trace
// filters another vertex or more than one.
void CheckAdaptiveTrace(const FilterConfig& config, const TraceOptions& trace);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_BOUNCE_OPTIONS_H
