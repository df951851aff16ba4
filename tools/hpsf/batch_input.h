// The batch a command judges: a recorded FILE.hpsfv as it is, or a scene (built-in name or file) traced at
// `--size` with the filter's seed. Shared by crosscheck and stats.
#ifndef HPSF_TOOLS_HPSF_BATCH_INPUT_H
#define HPSF_TOOLS_HPSF_BATCH_INPUT_H

#include <cstdint>
#include <string>

#include "core/record.h"
#include "tracer/path_tracer.h"

namespace hpsf {

// Bad input (a file, a scene, --size or a trace option) is an InputError or ConfigError naming it.
RecordBatch LoadOrTraceBatch(const std::string& input, const std::string& size, TraceOptions& trace,
                             std::uint32_t seed);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_BATCH_INPUT_H
