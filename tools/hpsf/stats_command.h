// `hpsf stats SCENE|FILE.hpsfv`: the figures that size a table for a scene and configuration (load, probe
// lengths and failures per probe limit, aliases per fingerprint width, records per cell, the jitter tests),
// each beside its theory; exit 1 (warn) when a measured rate exceeds its theory.
#ifndef HPSF_TOOLS_HPSF_STATS_COMMAND_H
#define HPSF_TOOLS_HPSF_STATS_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

// Sets *exit_code to 1 when a rate exceeds its theory.
void AddStatsCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_STATS_COMMAND_H
