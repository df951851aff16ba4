// The --vk-staging policy's names, apart from the device code: this file sees no Vulkan header, so the command
// line's option layer builds without the Vulkan host (the fuzz build's fuzz_cli).
#include <string>

#include "core/error.h"
#include "vulkan/vulkan_device.h"

namespace hpsf {

StagingPolicy ParseStagingPolicy(const std::string& text) {
  if (text == "auto") return StagingPolicy::kAuto;
  if (text == "always") return StagingPolicy::kAlways;
  if (text == "never") return StagingPolicy::kNever;
  throw ConfigError("--vk-staging", "'" + text + "' is not a staging policy; expected always, never or auto");
}

const char* ToString(StagingPolicy policy) {
  switch (policy) {
    case StagingPolicy::kAuto:
      return "auto";
    case StagingPolicy::kAlways:
      return "always";
    case StagingPolicy::kNever:
      return "never";
  }
  return "?";
}

}  // namespace hpsf
