// `hpsf check [GATE.json] [--shard I/N] [--junit OUT.xml] [--json] [--list] [--out DIR]`: the CI correctness
// gate, `hpsf check --merge DIR... [--junit OUT.xml] [--json]`, which merges its shards' reports
// (verifier/gate/check_report.h), and `hpsf check --schema`, which prints the gate file's JSON Schema. Every case of
// the gate file's matrix (verifier/gate/gate_file.h; without a file, the default gate) is validated first, then run
// as its own `hpsf` process, so a crash in a team's shader fails its case and not the gate; each failing case leaves
// its repro bundle in DIR/bundles and the run its report in DIR/check.json. Exit 0 every case passed, 2 a case
// failed or crashed, 3 bad input (the gate file, or a case's options, named with their place).
#ifndef HPSF_TOOLS_HPSF_CHECK_COMMAND_H
#define HPSF_TOOLS_HPSF_CHECK_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

void AddCheckCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_CHECK_COMMAND_H
