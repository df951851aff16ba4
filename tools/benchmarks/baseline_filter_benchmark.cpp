// The baselines beside hashed path space filtering, side by side on one batch (the Cornell box at 256x256, 4 spp,
// traced once): the radius search at HPSF's cell edge (scale 1, the accuracy HPSF approximates) and at twice it,
// the screen-space filter (9x9), and HPSF itself, as the emulator's fast mode runs it on every core and as the
// single-threaded exact-key reference. Items are records. Run:
//   build/default/bin/baseline_filter_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "emulated/emulated_filter.h"
#include "reference/radius_search_filter.h"
#include "reference/reference_filter.h"
#include "reference/screen_space_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

const RecordBatch& CornellBatch() {
  static const RecordBatch batch = [] {
    TraceOptions options;
    options.width = options.height = 256;
    options.samples_per_pixel = 4;
    return TraceRecords(LoadScene("cornell"), options).batch;
  }();
  return batch;
}

void Finish(benchmark::State& state, const RecordBatch& batch) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * batch.records.size()));
}

void BM_RadiusSearch(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  for (auto _ : state) {
    const NeighbourFilterResult result = RadiusSearchFilter(batch, FilterConfig{}, double(state.range(0)));
    benchmark::DoNotOptimize(result.image.pixels.data());
    state.counters["mean_neighbours"] = result.mean_neighbours;
  }
  Finish(state, batch);
}
BENCHMARK(BM_RadiusSearch)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ScreenSpace(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  for (auto _ : state) {
    const NeighbourFilterResult result = ScreenSpaceFilter(batch, FilterConfig{});
    benchmark::DoNotOptimize(result.image.pixels.data());
    state.counters["mean_neighbours"] = result.mean_neighbours;
  }
  Finish(state, batch);
}
BENCHMARK(BM_ScreenSpace)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_HashedEmulatedFast(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  FilterConfig config;
  config.capacity = 1u << 18;
  for (auto _ : state) {
    const EmulatedRun run = EmulatedFilter(batch, config, EmulatorOptions{});
    benchmark::DoNotOptimize(run.image.pixels.data());
  }
  Finish(state, batch);
}
BENCHMARK(BM_HashedEmulatedFast)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_HashedReference(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  for (auto _ : state) {
    const FilterResult result = ReferenceFilter(batch, FilterConfig{});
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  Finish(state, batch);
}
BENCHMARK(BM_HashedReference)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace hpsf

BENCHMARK_MAIN();
