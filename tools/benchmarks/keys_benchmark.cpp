// Keys per second for 2 million records: the shared key path in C++ on one core, and keys.comp on the Vulkan
// device (steady-state dispatches: pipeline creation and upload excluded). Run:
//   build/default/bin/keys_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <vector>

#include <benchmark/benchmark.h>

#include "core/key_batch.h"
#include "tools/benchmarks/benchmark_vulkan.h"
#include "verifier/generators/record_generators.h"

namespace hpsf {
namespace {

constexpr std::size_t kRecords = 2'000'000;

// A Cornell-box-sized scene: uniform vertices within 1000 units, level of detail on, jitter on.
struct KeyWorkload {
  KeyParams params;
  std::vector<Record> records;
};

const KeyWorkload& Workload() {
  static const KeyWorkload workload = [] {
    testing::KeyCase key_case;
    key_case.footprint_scale = 0.0025f;
    key_case.config.capacity = 1u << 21;
    KeyWorkload w;
    testing::RecordGenerator generator(2026);
    w.records = generator.Batch(testing::RecordKind::kUniform, key_case.Params(0), kRecords);
    w.params = key_case.Params(static_cast<std::uint32_t>(kRecords));
    return w;
  }();
  return workload;
}

void BM_KeysCpp(benchmark::State& state) {
  const KeyWorkload& w = Workload();
  std::vector<KeyResult> keys(w.records.size());  // kept across iterations, as the device's buffer is
  for (auto _ : state) {
    ComputeKeys(w.records, w.params, keys);
    benchmark::DoNotOptimize(keys.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRecords));
}
BENCHMARK(BM_KeysCpp)->Unit(benchmark::kMillisecond);

void BM_KeysVulkan(benchmark::State& state) {
  const KeyWorkload& w = Workload();
  KeyPass* pass = benchmarks::KeyPassOn(state, StagingPolicy::kAuto);
  if (!pass) return;
  pass->Upload(w.records);
  pass->Dispatch(w.params);  // warm-up: first-touch of the output buffer
  double device_ms = 0.0;
  for (auto _ : state) device_ms += pass->Dispatch(w.params);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRecords));
  state.counters["device_ms"] = device_ms / double(state.iterations());
  state.SetLabel(benchmarks::Device(state, StagingPolicy::kAuto)->info().name);
}
BENCHMARK(BM_KeysVulkan)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace hpsf

HPSF_BENCHMARK_MAIN();
