// The command line's reference page (docs/reference/cli.md), written from the very CLI11 definitions `hpsf` parses
// with: every command and subcommand, each option's names, type, default and help text. `cli_reference` writes it;
// a test fails when the committed page differs from what the definitions give.
#ifndef HPSF_TOOLS_HPSF_CLI_REFERENCE_H
#define HPSF_TOOLS_HPSF_CLI_REFERENCE_H

#include <string>

#include <CLI/CLI.hpp>

namespace hpsf {

std::string CliReferenceMarkdown(const CLI::App& app);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_CLI_REFERENCE_H
