// `hpsf reference SCENE --spp N`: the converged image of a scene (plain path tracing at many samples, with each
// pixel's variance), rendered once and cached (tools/hpsf/reference_cache.h), to measure error against.
#ifndef HPSF_TOOLS_HPSF_REFERENCE_COMMAND_H
#define HPSF_TOOLS_HPSF_REFERENCE_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

void AddReferenceCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_REFERENCE_COMMAND_H
