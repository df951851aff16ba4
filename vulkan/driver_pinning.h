// Keeps the Vulkan drivers (ICDs) loaded until the process exits, in AddressSanitizer builds only. LeakSanitizer
// checks at exit, after the Vulkan loader has unloaded the driver at vkDestroyInstance: memory a driver holds in its
// own statics (Mesa 22.3.6's lavapipe allocates some once, in a pthread_once under vkEnumeratePhysicalDevices) is
// then unreachable and reported as a leak in "<unknown module>", failing every Vulkan test of the asan run. Kept
// loaded, the driver's statics keep that memory reachable, as they do in any process. Other builds: nothing.
#ifndef HPSF_VULKAN_DRIVER_PINNING_H
#define HPSF_VULKAN_DRIVER_PINNING_H

namespace hpsf {

// Marks every loaded library named libvulkan_* (the Mesa drivers) RTLD_NODELETE. Call after the instance has
// enumerated its physical devices (the drivers are loaded then).
void KeepVulkanDriversLoadedUnderSanitizers();

}  // namespace hpsf

#endif  // HPSF_VULKAN_DRIVER_PINNING_H
