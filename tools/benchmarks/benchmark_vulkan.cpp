#include "tools/benchmarks/benchmark_vulkan.h"

#include "vulkan/vulkan_objects.h"

namespace hpsf::benchmarks {
namespace {

VulkanObjects objects;

}  // namespace

VulkanDevice* Device(benchmark::State& state, StagingPolicy staging) {
  try {
    return &objects.Device(staging);
  } catch (const VulkanUnavailable& e) {
    state.SkipWithError(e.what());
    return nullptr;
  }
}

KeyPass* KeyPassOn(benchmark::State& state, StagingPolicy staging) {
  return Device(state, staging) ? &objects.KeyPassOn(staging) : nullptr;
}

VulkanFilter* FilterOn(benchmark::State& state, StagingPolicy staging) {
  return Device(state, staging) ? &objects.FilterOn(staging) : nullptr;
}

void ReleaseVulkan() { objects.Release(); }

}  // namespace hpsf::benchmarks
