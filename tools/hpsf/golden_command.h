// `hpsf golden check` renders every case of golden/manifest.json with each of its backends and compares it with
// its golden (exit 0 pass, 1 warn, 2 fail, 3 a bad manifest); a case that does not pass leaves the new image,
// the heatmap and a report beside its golden. `hpsf golden bless [CASE...]` is the only writer of goldens and
// says what changed.
#ifndef HPSF_TOOLS_HPSF_GOLDEN_COMMAND_H
#define HPSF_TOOLS_HPSF_GOLDEN_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

void AddGoldenCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_GOLDEN_COMMAND_H
