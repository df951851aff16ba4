// What main hands every command: where it leaves its exit code, and whether it stops once its options are
// resolved. The second is how the option tests (tools/hpsf/command_options_test.cpp) run every command's real
// option layer, its resolvers included, without reading an input or writing an output.
#ifndef HPSF_TOOLS_HPSF_COMMAND_CONTEXT_H
#define HPSF_TOOLS_HPSF_COMMAND_CONTEXT_H

#include "core/error.h"

namespace hpsf {

struct CommandContext {
  int exit_code = kExitOk;
  // Parse and resolve the options (a bad one is a CLI11 ParseError or an InputError), then return: no file is
  // read, no device opened, nothing written.
  bool options_only = false;
};

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_COMMAND_CONTEXT_H
