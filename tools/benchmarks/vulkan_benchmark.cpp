// The Vulkan backend on the 2-million-record batch (the Cornell box at 1080p, 1 spp) into a 2^21-slot table,
// beside the emulator's fast mode in the same run, with the staging policy auto, always and never; counters split
// each Vulkan run into upload, accumulate and resolve (device timestamps), filter (their sum) and read-back, with
// the transfers' GB/s. Run:
//   build/default/bin/vulkan_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "emulated/emulated_backend.h"
#include "tools/benchmarks/benchmark_vulkan.h"
#include "tools/benchmarks/cornell_frame.h"

namespace hpsf {
namespace {

FilterConfig TableConfig(Accumulation accumulation) {
  FilterConfig config;
  config.capacity = 1u << 21;
  config.probe_limit = 16;
  config.accumulation = accumulation;
  return config;
}

// Frame after frame through the backend, which keeps its arrays as the Vulkan filter keeps its buffers.
void BM_EmulatedFast(benchmark::State& state) {
  EmulatedBackend backend{EmulatorOptions{}};
  backend.FilterFrame(CornellFrame(), TableConfig(Accumulation::kFixed64));  // first touch of its arrays
  for (auto _ : state) {
    backend.Reset();
    benchmark::DoNotOptimize(backend.FilterFrame(CornellFrame(), TableConfig(Accumulation::kFixed64)).pixels.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_EmulatedFast)->Unit(benchmark::kMillisecond)->UseRealTime();

// Arguments: accumulation (0 fixed64, 1 float32) and staging (0 auto, 1 always, 2 never).
void BM_Vulkan(benchmark::State& state) {
  const Accumulation accumulation = state.range(0) == 0 ? Accumulation::kFixed64 : Accumulation::kFloat32;
  const StagingPolicy staging = StagingPolicy(state.range(1));
  VulkanFilter* filter = benchmarks::FilterOn(state, staging);
  if (!filter) return;
  const VulkanDeviceInfo& device = benchmarks::Device(state, staging)->info();
  state.SetLabel(std::string(accumulation == Accumulation::kFixed64 ? "fixed64" : "float32") +
                 (device.staged ? ", staged" : ", mapped") + " on " + device.name);
  VulkanTimings sum;
  for (auto _ : state) {
    VulkanRun run = filter->Run(CornellFrame(), TableConfig(accumulation));
    benchmark::DoNotOptimize(run.image.pixels.data());
    const VulkanTimings& t = run.timings;
    sum.upload_ms += t.upload_ms;
    sum.upload_copy_ms += t.upload_copy_ms;
    sum.accumulate_ms += t.accumulate_ms;
    sum.resolve_ms += t.resolve_ms;
    sum.read_back_copy_ms += t.read_back_copy_ms;
    sum.read_back_ms += t.read_back_ms;
    sum.upload_bytes = t.upload_bytes;
    sum.read_back_bytes = t.read_back_bytes;
  }
  const double n = double(state.iterations());
  state.counters["upload_ms"] = (sum.upload_ms + sum.upload_copy_ms) / n;
  state.counters["accumulate_ms"] = sum.accumulate_ms / n;
  state.counters["resolve_ms"] = sum.resolve_ms / n;
  state.counters["filter_ms"] = sum.FilterMs() / n;
  state.counters["read_back_ms"] = (sum.read_back_copy_ms + sum.read_back_ms) / n;
  // The device's copies apart (0 when mapped): on a discrete GPU they tell the bus from the host's first touch.
  state.counters["upload_copy_ms"] = sum.upload_copy_ms / n;
  state.counters["read_back_copy_ms"] = sum.read_back_copy_ms / n;
  state.counters["upload_GBps"] = double(sum.upload_bytes) * n / (sum.UploadMs() * 1e6);
  state.counters["read_back_GBps"] = double(sum.read_back_bytes) * n / (sum.ReadBackMs() * 1e6);
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_Vulkan)->ArgsProduct({{0, 1}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

// fixed64 under the staging policy auto with each key identity (0 fingerprints, 32-bit tags; 1 full keys, 64-bit
// tags), side by side in one run: the accumulate's cost of the wider tags and their read-back.
void BM_VulkanKeyIdentity(benchmark::State& state) {
  VulkanFilter* filter = benchmarks::FilterOn(state, StagingPolicy::kAuto);
  if (!filter) return;
  FilterConfig config = TableConfig(Accumulation::kFixed64);
  config.key_identity = state.range(0) == 0 ? KeyIdentity::kFingerprint : KeyIdentity::kFull;
  state.SetLabel(ToString(config.key_identity));
  double accumulate_ms = 0, read_back_ms = 0;
  for (auto _ : state) {
    VulkanRun run = filter->Run(CornellFrame(), config);
    benchmark::DoNotOptimize(run.image.pixels.data());
    accumulate_ms += run.timings.accumulate_ms;
    read_back_ms += run.timings.read_back_copy_ms + run.timings.read_back_ms;
  }
  state.counters["accumulate_ms"] = accumulate_ms / double(state.iterations());
  state.counters["read_back_ms"] = read_back_ms / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_VulkanKeyIdentity)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// Multi-level accumulation (--levels 1, 2, 3) and the neighbourhood search (second argument 1), with --min-count the
// third argument wherever either is on and --filter-width the fourth, fixed64, staging auto, side by side: the
// accumulate's and the resolve's device time, and the share of records that search. At a filter width of 32 pixels
// hardly a cell holds fewer than 2 records: what the search costs where it has (almost) nothing to do.
void BM_VulkanLevels(benchmark::State& state) {
  VulkanFilter* filter = benchmarks::FilterOn(state, StagingPolicy::kAuto);
  if (!filter) return;
  FilterConfig config = TableConfig(Accumulation::kFixed64);
  config.levels = std::uint32_t(state.range(0));
  config.neighbour_search = state.range(1) != 0;
  config.min_count = config.levels > 1 || config.neighbour_search ? std::uint32_t(state.range(2)) : 1;
  config.filter_width_px = float(state.range(3));
  state.SetLabel("levels " + std::to_string(config.levels) + (config.neighbour_search ? ", search" : "") +
                 ", min-count " + std::to_string(config.min_count) + ", filter width " +
                 std::to_string(state.range(3)));
  double accumulate_ms = 0, resolve_ms = 0, searched = 0;
  for (auto _ : state) {
    VulkanRun run = filter->Run(CornellFrame(), config);
    benchmark::DoNotOptimize(run.image.pixels.data());
    accumulate_ms += run.timings.accumulate_ms;
    resolve_ms += run.timings.resolve_ms;
    searched = double(run.records_searched) / double(kFrameRecords);
  }
  state.counters["accumulate_ms"] = accumulate_ms / double(state.iterations());
  state.counters["resolve_ms"] = resolve_ms / double(state.iterations());
  state.counters["searched"] = searched;
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kFrameRecords);
}
BENCHMARK(BM_VulkanLevels)
    ->Args({1, 0, 1, 4})
    ->Args({2, 0, 4, 4})
    ->Args({3, 0, 4, 4})
    ->Args({1, 1, 2, 4})
    ->Args({1, 1, 4, 4})
    ->Args({1, 1, 8, 4})
    ->Args({3, 1, 4, 4})
    ->Args({1, 0, 1, 32})
    ->Args({1, 1, 2, 32})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace hpsf

HPSF_BENCHMARK_MAIN();
