// `hpsf crosscheck SCENE|FILE.hpsfv`: the backends on one batch or a sequence of frames, the verdict per level
// and the quality figures; exit 0 when the contract holds, 2 when it does not, and then a repro bundle.
#ifndef HPSF_TOOLS_HPSF_CROSSCHECK_COMMAND_H
#define HPSF_TOOLS_HPSF_CROSSCHECK_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

// Sets *exit_code to 2 when the contract does not hold.
void AddCrosscheckCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_CROSSCHECK_COMMAND_H
