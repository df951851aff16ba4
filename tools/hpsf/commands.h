// Every subcommand of hpsf, registered on one CLI11 App: main's list, which the option tests share.
#ifndef HPSF_TOOLS_HPSF_COMMANDS_H
#define HPSF_TOOLS_HPSF_COMMANDS_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

// The commands keep a reference to `context`, which must outlive the App's parse.
// What `hpsf --help` says hpsf is.
inline constexpr const char* kHpsfDescription =
    "hpsf: makes GPU hash tables for hashed path space filtering trustworthy";

void AddCommands(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_COMMANDS_H
