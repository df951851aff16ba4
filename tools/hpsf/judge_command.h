// `hpsf judge CAPTURE...`: judges frames captured from a team's own engine (docs/reference/capture-format.md) by the
// table checker and the contract, offline, as text, JSON or JUnit; exit 0 when every capture holds, 2 when one does
// not, 3 for a capture that is not one (nothing is printed then).
#ifndef HPSF_TOOLS_HPSF_JUDGE_COMMAND_H
#define HPSF_TOOLS_HPSF_JUDGE_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

void AddJudgeCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_JUDGE_COMMAND_H
