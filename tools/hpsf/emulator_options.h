// The emulator's options and the Vulkan backend's, as render, replay and crosscheck take them: registered on a
// command and resolved into validated EmulatorOptions. No Vulkan host code, so the option layer is fuzzed alone
// (tools/fuzz/fuzz_cli.cpp).
#ifndef HPSF_TOOLS_HPSF_EMULATOR_OPTIONS_H
#define HPSF_TOOLS_HPSF_EMULATOR_OPTIONS_H

#include <string>

#include <CLI/CLI.hpp>

#include "emulated/emulated_filter.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf {

struct EmulatorFlags {
  std::string mode = "fast";
  std::string defect = "none";
  EmulatorOptions options;
  VulkanBackendOptions vulkan;  // --vk-device, --accumulate-spv, --vk-staging
};

void AddEmulatorOptions(CLI::App& command, EmulatorFlags& flags);
EmulatorOptions ResolveEmulatorOptions(const EmulatorFlags& flags);  // ConfigError naming the option

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_EMULATOR_OPTIONS_H
