// `hpsf device`: opens the Vulkan device the other commands would use and prints what it is and supports.
#ifndef HPSF_TOOLS_HPSF_DEVICE_COMMAND_H
#define HPSF_TOOLS_HPSF_DEVICE_COMMAND_H

#include <CLI/CLI.hpp>

#include "tools/hpsf/command_context.h"

namespace hpsf {

void AddDeviceCommand(CLI::App& app, CommandContext& context);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_DEVICE_COMMAND_H
