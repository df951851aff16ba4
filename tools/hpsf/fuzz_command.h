// `hpsf fuzz`: adversarial batches (verifier/fuzzing/adversarial_case.h) against the emulated backend, the Vulkan
// backend or a team's own accumulate shader, each judged by the table checker and the cross-check contract. The
// first failure is shrunk to a minimal batch and written as a repro bundle that `hpsf crosscheck` reproduces
// exactly. Exit 0 clean, 2 a failure found, 3 bad input.
#ifndef HPSF_TOOLS_HPSF_FUZZ_COMMAND_H
#define HPSF_TOOLS_HPSF_FUZZ_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

void AddFuzzCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_FUZZ_COMMAND_H
