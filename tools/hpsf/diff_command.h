// `hpsf diff A.exr B.exr`: compares a test image A with a reference B (the metrics, SSIM, the hpsf: metadata),
// judges the difference by one written rule (verifier/metrics/diff_verdict.h) and can write an error heatmap and a
// self-contained HTML report. Exit 0 pass, 1 warn, 2 fail, 3 bad input with nothing written.
#ifndef HPSF_TOOLS_HPSF_DIFF_COMMAND_H
#define HPSF_TOOLS_HPSF_DIFF_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

void AddDiffCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_DIFF_COMMAND_H
