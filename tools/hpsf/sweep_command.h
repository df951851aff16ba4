// `hpsf sweep SCENE --grid "..."`: what accuracy costs in time. Every configuration of the grid
// (tools/hpsf/sweep_grid.h) is traced and filtered with K seeds, timed per phase, and measured against the scene's
// converged image (`hpsf reference`, cached): MSE, relMSE, SSIM, and the MSE split into bias^2 and variance
// (verifier/metrics/error_split.h); probe failures and aliased slots for the hashed backends. Each finished
// configuration is kept in OUT/configs/ and not run again (a sweep resumes where it stopped, and --shard I/N runs
// every N-th configuration, so shards in one OUT fill it); OUT/sweep.csv and OUT/sweep.json hold every finished
// configuration in grid order.
#ifndef HPSF_TOOLS_HPSF_SWEEP_COMMAND_H
#define HPSF_TOOLS_HPSF_SWEEP_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

void AddSweepCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_SWEEP_COMMAND_H
