#include "vulkan/driver_pinning.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HPSF_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define HPSF_ADDRESS_SANITIZER 1
#endif

#ifdef HPSF_ADDRESS_SANITIZER
#include <dlfcn.h>
#include <link.h>

#include <cstring>
#endif

namespace hpsf {

void KeepVulkanDriversLoadedUnderSanitizers() {
#ifdef HPSF_ADDRESS_SANITIZER
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) {
        const char* name = info->dlpi_name;
        if (name != nullptr && std::strstr(name, "/libvulkan_") != nullptr) {
          // RTLD_NOLOAD only promotes the flags of a library already loaded; the handle's reference is never
          // released, on purpose.
          dlopen(name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        }
        return 0;
      },
      nullptr);
#endif
}

}  // namespace hpsf
