// The batch a command judges: a recorded FILE.hpsfv as it is, or a scene (built-in name or file) traced at
// `--size` with the filter's seed. Shared by crosscheck and stats.
#ifndef HPSF_TOOLS_HPSF_BATCH_INPUT_H
#define HPSF_TOOLS_HPSF_BATCH_INPUT_H

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/record.h"
#include "tracer/path_tracer.h"

namespace hpsf {

// For a scene input, sets `trace`'s size from `size` and its seed, and checks it (ConfigError naming the option);
// a record file is not traced, so its trace options are not checked.
void ResolveTraceOptions(const std::string& input, const std::string& size, TraceOptions& trace, std::uint32_t seed);

// `trace` as ResolveTraceOptions left it. A bad file or scene is an InputError naming it.
RecordBatch LoadOrTraceBatch(const std::string& input, const TraceOptions& trace);

// --transport on over frames none of which carries scattered vertices (a record file made without them) would
// transport nothing: a ConfigError naming --transport and the input.
void CheckTransportInput(const std::string& input, std::span<const RecordBatch> frames, const FilterConfig& config);

// Whether the input names a recorded .hpsfv file rather than a scene.
bool IsRecordFile(const std::string& input);

// A sequence: every frame of a record file, or `frames` frames of a scene traced from trace.frame on (the scene built
// as config's effect plan says).
std::vector<RecordBatch> LoadOrTraceFrames(const std::string& input, const TraceOptions& trace, std::uint32_t frames,
                                           const FilterConfig& config);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_BATCH_INPUT_H
