// The Vulkan backend on the 2-million-record batch (the Cornell box at 1080p, 1 spp) into a 2^21-slot table,
// beside the emulator's fast mode in the same run; counters split each Vulkan run into upload, accumulate and
// resolve (device timestamps) and read-back. Run:
//   build/default/bin/vulkan_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "emulated/emulated_filter.h"
#include "tools/benchmarks/cornell_frame.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf {
namespace {

FilterConfig TableConfig(Accumulation accumulation) {
  FilterConfig config;
  config.capacity = 1u << 21;
  config.probe_limit = 16;
  config.accumulation = accumulation;
  return config;
}

void BM_EmulatedFast(benchmark::State& state) {
  for (auto _ : state) {
    EmulatedRun run = EmulatedFilter(CornellFrame(), TableConfig(Accumulation::kFixed64), EmulatorOptions{});
    benchmark::DoNotOptimize(run.image.pixels.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_EmulatedFast)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Vulkan(benchmark::State& state) {
  static VulkanDevice device;
  static VulkanFilter filter(device);
  const Accumulation accumulation = state.range(0) == 0 ? Accumulation::kFixed64 : Accumulation::kFloat32;
  state.SetLabel(std::string(accumulation == Accumulation::kFixed64 ? "fixed64 on " : "float32 on ") + device.info().name);
  for (auto _ : state) {
    VulkanRun run = filter.Run(CornellFrame(), TableConfig(accumulation));
    benchmark::DoNotOptimize(run.image.pixels.data());
    state.counters["upload_ms"] = run.timings.upload_ms;
    state.counters["accumulate_ms"] = run.timings.accumulate_ms;
    state.counters["resolve_ms"] = run.timings.resolve_ms;
    state.counters["read_back_ms"] = run.timings.read_back_ms;
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_Vulkan)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace hpsf

BENCHMARK_MAIN();
