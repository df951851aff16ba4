// The backends hpsf has, by name, with what each can do: every command, the cross-check, the sweep and the gate
// validate a backend name here and read its capabilities here, never by comparing strings of their own. Each is
// made by MakeBackend (verifier/contract/backend_factory.h), behind the one interface of core/backend.h.
#ifndef HPSF_CORE_BACKEND_REGISTRY_H
#define HPSF_CORE_BACKEND_REGISTRY_H

#include <span>
#include <string>

namespace hpsf {

enum class BackendKind { kReference, kEmulated, kVulkan };

struct BackendInfo {
  const char* name;
  BackendKind kind;
  bool hashed;             // keeps a hash table: judged by the table checker, beside the reference
  bool on_device;          // runs on a Vulkan device, which it needs to be made
  bool runs_user_shaders;  // takes a team's SPIR-V in place of its own passes (--accumulate-spv, --eviction-spv)
  const char* summary;
};

// In the order help texts list them.
std::span<const BackendInfo> RegisteredBackends();

// The backend called `name`; a ConfigError naming `option` and listing the backends otherwise. hashed_only: the
// reference is refused too (where a backend is judged beside it).
const BackendInfo& FindBackend(const std::string& name, const std::string& option, bool hashed_only = false);

// "reference, emulated, vulkan" (or the hashed ones), for messages and help texts.
std::string BackendNames(bool hashed_only = false);

}  // namespace hpsf

#endif  // HPSF_CORE_BACKEND_REGISTRY_H
