// A second frame from a table loaded with a state no short test reaches by filtering (a count near its word's
// limit, as a long sequence would leave it), on the emulator and on Vulkan mapped and staged. The overflow tests of
// 64-bit counts and of packed-decimal's count words share it.
#ifndef HPSF_PROPERTY_TESTS_LOADED_TABLE_FRAMES_H
#define HPSF_PROPERTY_TESTS_LOADED_TABLE_FRAMES_H

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/hashed_run.h"
#include "emulated/emulated_filter.h"
#include "property_tests/vulkan_test_devices.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf::testing {

struct LoadedFrame {
  HashedRun run;
  std::string name;
};

// Frame 0 of `batch` on the emulator, its table loaded with `count` in record 0's slot (left in `loaded`, the
// table before frame 1, for the checker); then frame 1 from it on the emulator with `kernel` and on Vulkan with the
// shader `accumulate_spv` (empty: built in).
inline std::vector<LoadedFrame> FramesFromLoadedCount(std::uint64_t count, const RecordBatch& batch,
                                                      FilterConfig config, HashTableDump& loaded,
                                                      AccumulateKernelFn kernel = AccumulateKernel,
                                                      const std::string& accumulate_spv = "") {
  EmulatedRun first = EmulatedFilter(batch, config, EmulatorOptions{});
  loaded = std::move(first.table);
  loaded.counts[first.placements[0]] = count;
  config.frame = 1;
  std::vector<LoadedFrame> frames;
  frames.push_back({EmulatedFilter(batch, config, EmulatorOptions{}, kernel, &loaded), "emulated"});
  for (const StagingPolicy staging : kStagingPolicies) {
    VulkanFilter vulkan(TestDevice(staging), accumulate_spv);
    vulkan.LoadTable(loaded);
    frames.push_back({vulkan.Run(batch, config, true), std::string("vulkan, staging ") + ToString(staging)});
  }
  return frames;
}

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_LOADED_TABLE_FRAMES_H
