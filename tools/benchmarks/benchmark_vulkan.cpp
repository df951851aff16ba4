#include "tools/benchmarks/benchmark_vulkan.h"

#include <memory>

namespace hpsf::benchmarks {
namespace {

struct PolicyObjects {
  std::unique_ptr<VulkanDevice> device;
  std::unique_ptr<KeyPass> key_pass;
  std::unique_ptr<VulkanFilter> filter;
};

PolicyObjects objects[3];  // by StagingPolicy

}  // namespace

VulkanDevice* Device(benchmark::State& state, StagingPolicy staging) {
  PolicyObjects& o = objects[int(staging)];
  if (!o.device) {
    try {
      o.device = std::make_unique<VulkanDevice>("", staging);
    } catch (const VulkanUnavailable& e) {
      state.SkipWithError(e.what());
      return nullptr;
    }
  }
  return o.device.get();
}

KeyPass* KeyPassOn(benchmark::State& state, StagingPolicy staging) {
  VulkanDevice* device = Device(state, staging);
  if (!device) return nullptr;
  PolicyObjects& o = objects[int(staging)];
  if (!o.key_pass) o.key_pass = std::make_unique<KeyPass>(*device);
  return o.key_pass.get();
}

VulkanFilter* FilterOn(benchmark::State& state, StagingPolicy staging) {
  VulkanDevice* device = Device(state, staging);
  if (!device) return nullptr;
  PolicyObjects& o = objects[int(staging)];
  if (!o.filter) o.filter = std::make_unique<VulkanFilter>(*device);
  return o.filter.get();
}

void ReleaseVulkan() {
  for (PolicyObjects& o : objects) {  // passes and filters before their device
    o.filter.reset();
    o.key_pass.reset();
    o.device.reset();
  }
}

}  // namespace hpsf::benchmarks
