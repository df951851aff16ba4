#include "tools/hpsf/device_command.h"

#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "vulkan/vulkan_device.h"

namespace hpsf {
namespace {

struct DeviceOptions {
  std::string vk_device;
  StagingPolicy staging = StagingPolicy::kAuto;
  bool json = false;
};

void RunDevice(const DeviceOptions& options) {
  VulkanDevice device(options.vk_device, options.staging);
  const VulkanDeviceInfo& info = device.info();
  if (options.json) {
    nlohmann::json report = {{"version", 1},
                             {"name", info.name},
                             {"type", info.type},
                             {"driver_name", info.driver_name},
                             {"driver_info", info.driver_info},
                             {"api_version", info.api_version},
                             {"subgroup_size", info.subgroup_size},
                             {"staged", info.staged},
                             {"memory", info.memory}};
    std::cout << report.dump(2) << "\n";
  } else {
    std::cout << info.name << " (" << info.type << "), driver " << info.driver_name << " " << info.driver_info
              << ", Vulkan " << info.api_version << ", subgroup size " << info.subgroup_size
              << "; every required feature present\nmemory: " << info.memory << "\n";
  }
}

}  // namespace

void AddDeviceCommand(CLI::App& app, CommandContext& context) {
  auto options = std::make_shared<DeviceOptions>();
  CLI::App* command = app.add_subcommand("device", "Open the Vulkan device hpsf would use and describe it");
  command->add_option("--vk-device", options->vk_device, "Use the device whose name contains this text");
  command
      ->add_option_function<std::string>(
          "--vk-staging", [options](const std::string& text) { options->staging = ParseStagingPolicy(text); },
          "Staging buffers: always, never or auto")
      ->default_str("auto");
  command->add_flag("--json", options->json, "Print a JSON report");
  command->callback([options, &context] {
    if (!context.options_only) RunDevice(*options);
  });
}

}  // namespace hpsf
