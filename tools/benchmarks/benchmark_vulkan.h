// The Vulkan objects a benchmark binary shares (vulkan/vulkan_objects.h), one set per staging policy, released by
// the binary's main once the benchmarks have run: a device destroyed during static destruction crashed NVIDIA's
// driver at exit. Use HPSF_BENCHMARK_MAIN() in place of BENCHMARK_MAIN().
#ifndef HPSF_TOOLS_BENCHMARKS_BENCHMARK_VULKAN_H
#define HPSF_TOOLS_BENCHMARKS_BENCHMARK_VULKAN_H

#include <benchmark/benchmark.h>

#include "vulkan/key_pass.h"
#include "vulkan/vulkan_device.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf::benchmarks {

// Null after a benchmark was skipped with the reason, when no device opens.
VulkanDevice* Device(benchmark::State& state, StagingPolicy staging);
KeyPass* KeyPassOn(benchmark::State& state, StagingPolicy staging);
VulkanFilter* FilterOn(benchmark::State& state, StagingPolicy staging);
void ReleaseVulkan();

}  // namespace hpsf::benchmarks

#define HPSF_BENCHMARK_MAIN()                                         \
  int main(int argc, char** argv) {                                   \
    benchmark::Initialize(&argc, argv);                               \
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1; \
    benchmark::RunSpecifiedBenchmarks();                              \
    hpsf::benchmarks::ReleaseVulkan();                                \
    benchmark::Shutdown();                                            \
    return 0;                                                         \
  }

#endif  // HPSF_TOOLS_BENCHMARKS_BENCHMARK_VULKAN_H
