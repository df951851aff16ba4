// `hpsf device`: opens the Vulkan device the other commands would use and prints what it is and supports.
#ifndef HPSF_TOOLS_HPSF_DEVICE_COMMAND_H
#define HPSF_TOOLS_HPSF_DEVICE_COMMAND_H

#include <CLI/CLI.hpp>

namespace hpsf {

void AddDeviceCommand(CLI::App& app);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_DEVICE_COMMAND_H
