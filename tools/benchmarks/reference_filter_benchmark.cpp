// Records per second through the exact-key reference filter, on a Cornell box batch (256x256, 4 spp, traced
// once). Run: build/default/bin/reference_filter_benchmark --benchmark_repetitions=5
// --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "reference/reference_filter.h"
#include "tools/benchmarks/cornell_batch.h"

namespace hpsf {
namespace {

void BM_ReferenceFilter(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  FilterConfig config;
  config.accumulation = state.range(0) == 0 ? Accumulation::kFixed64 : Accumulation::kFloat32;
  for (auto _ : state) {
    FilterResult result = ReferenceFilter(batch, config);
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * batch.records.size()));
  state.SetLabel(config.accumulation == Accumulation::kFixed64 ? "fixed64" : "float32");
}
BENCHMARK(BM_ReferenceFilter)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// fixed64 with --levels 1, 2, 3 (--min-count 4 above one level): the exact map's cost of each coarser level.
void BM_ReferenceLevels(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  FilterConfig config;
  config.levels = std::uint32_t(state.range(0));
  config.neighbour_search = state.range(1) != 0;
  config.min_count = config.levels > 1 || config.neighbour_search ? 4 : 1;
  for (auto _ : state) {
    FilterResult result = ReferenceFilter(batch, config);
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * batch.records.size()));
  state.SetLabel("levels " + std::to_string(config.levels) + (config.neighbour_search ? ", search" : ""));
}
BENCHMARK(BM_ReferenceLevels)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({3, 0})
    ->Args({1, 1})
    ->Args({3, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hpsf

BENCHMARK_MAIN();
