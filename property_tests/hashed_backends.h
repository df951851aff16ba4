// The hashed backends the frame tests run side by side behind the Backend interface: the emulator fast and
// faithful (warps of 8, a random schedule) and Vulkan mapped and staged, optionally with a broken reclaim.
#ifndef HPSF_PROPERTY_TESTS_HASHED_BACKENDS_H
#define HPSF_PROPERTY_TESTS_HASHED_BACKENDS_H

#include <memory>
#include <string>
#include <vector>

#include "core/backend.h"
#include "core/hashed_run.h"
#include "emulated/emulated_backend.h"
#include "property_tests/vulkan_test_devices.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {

struct HashedBackend {
  std::string name;
  std::unique_ptr<Backend> backend;
};

// eviction_kernels and eviction_spv: the emulator's eviction kernels and the eviction shader (empty: the built-in
// one).
inline std::vector<HashedBackend> HashedBackends(EvictionKernels eviction_kernels = {},
                                                 const std::string& eviction_spv = "") {
  std::vector<HashedBackend> backends;
  backends.push_back(
      {"emulated fast", std::make_unique<EmulatedBackend>(EmulatorOptions{}, AccumulateKernel, eviction_kernels)});
  EmulatorOptions faithful;
  faithful.mode = simt::Mode::kFaithful;
  faithful.warp_size = 8;
  faithful.schedule = "random:7";
  backends.push_back(
      {"emulated faithful", std::make_unique<EmulatedBackend>(faithful, AccumulateKernel, eviction_kernels)});
  for (const StagingPolicy staging : kStagingPolicies) {
    backends.push_back({std::string("vulkan, staging ") + ToString(staging),
                        std::make_unique<VulkanBackend>(TestDevice(staging), "", eviction_spv)});
  }
  return backends;
}

// The last frame's run of a hashed backend.
inline const HashedRun& RunOf(const Backend& backend) { return *backend.LastHashedRun(); }

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_HASHED_BACKENDS_H
