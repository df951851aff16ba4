#include "core/backend_registry.h"

#include <array>

#include "core/error.h"

namespace hpsf {
namespace {

constexpr std::array<BackendInfo, 3> kBackends = {{
    {"reference", BackendKind::kReference, false, false, false, "the exact map of cells: the oracle"},
    {"emulated", BackendKind::kEmulated, true, false, false,
     "the hash table on the emulated GPU, deterministic by seed"},
    {"vulkan", BackendKind::kVulkan, true, true, true, "the hash table in Vulkan compute shaders on a device"},
}};

}  // namespace

std::span<const BackendInfo> RegisteredBackends() { return kBackends; }

std::string BackendNames(bool hashed_only) {
  std::string names;
  for (const BackendInfo& b : kBackends) {
    if (hashed_only && !b.hashed) continue;
    names += (names.empty() ? "" : ", ") + std::string(b.name);
  }
  return names;
}

const BackendInfo& FindBackend(const std::string& name, const std::string& option, bool hashed_only) {
  for (const BackendInfo& b : kBackends) {
    if (name != b.name) continue;
    if (hashed_only && !b.hashed) break;
    return b;
  }
  throw ConfigError(option, "'" + name + "' is not " + (hashed_only ? "a hashed backend" : "available") +
                                "; this build has: " + BackendNames(hashed_only));
}

}  // namespace hpsf
