// The baselines beside hashed path space filtering, side by side on one batch (the Cornell box at 256x256, 4 spp,
// traced once): the radius search at HPSF's cell edge (scale 1, the accuracy HPSF approximates) and at twice it,
// the screen-space filter (9x9), plain path tracing (the batch unfiltered), and HPSF itself, as the emulator's fast
// mode runs it on every core and as the single-threaded exact-key reference. Items are records; the counter relmse
// is each image's relMSE against a converged image of the same view (256x256 at 1024 spp, rendered once per
// process, about a minute on 2 cores). Run:
//   build/default/bin/baseline_filter_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "emulated/emulated_filter.h"
#include "reference/radius_search_filter.h"
#include "reference/reference_filter.h"
#include "reference/screen_space_filter.h"
#include "tools/benchmarks/cornell_batch.h"
#include "tools/hpsf/converged_reference.h"
#include "tracer/scene_file.h"
#include "verifier/metrics/channel_image.h"
#include "verifier/metrics/image_metrics.h"

namespace hpsf {
namespace {

const ChannelImage& Converged() {
  static const ChannelImage converged = [] {
    ReferenceRequest request;
    request.trace.width = request.trace.height = 256;
    request.trace.seed = 1000;  // not the batch's seed: the error of an image is measured against other samples
    request.samples_per_pixel = 1024;
    request.pass_samples = 16;
    return ColourChannels(RenderConverged(LoadScene("cornell"), request).mean);
  }();
  return converged;
}

void Finish(benchmark::State& state, const RecordBatch& batch, const Image& image) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * batch.records.size()));
  state.counters["relmse"] = ComputeMetrics(ColourChannels(image), Converged()).relmse;
}

void BM_PlainPathTracing(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  Image image;
  for (auto _ : state) {
    image = UnfilteredImage(batch);
    benchmark::DoNotOptimize(image.pixels.data());
  }
  Finish(state, batch, image);
}
BENCHMARK(BM_PlainPathTracing)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RadiusSearch(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  NeighbourFilterResult result;
  for (auto _ : state) {
    result = RadiusSearchFilter(batch, FilterConfig{}, double(state.range(0)));
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  state.counters["mean_neighbours"] = result.mean_neighbours;
  Finish(state, batch, result.image);
}
BENCHMARK(BM_RadiusSearch)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ScreenSpace(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  NeighbourFilterResult result;
  for (auto _ : state) {
    result = ScreenSpaceFilter(batch, FilterConfig{});
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  state.counters["mean_neighbours"] = result.mean_neighbours;
  Finish(state, batch, result.image);
}
BENCHMARK(BM_ScreenSpace)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_HashedEmulatedFast(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  FilterConfig config;
  config.capacity = 1u << 18;
  Image image;
  for (auto _ : state) {
    const EmulatedRun run = EmulatedFilter(batch, config, EmulatorOptions{});
    benchmark::DoNotOptimize(run.image.pixels.data());
    image = run.image;
  }
  Finish(state, batch, image);
}
BENCHMARK(BM_HashedEmulatedFast)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_HashedReference(benchmark::State& state) {
  const RecordBatch& batch = CornellBatch();
  Image image;
  for (auto _ : state) {
    const FilterResult result = ReferenceFilter(batch, FilterConfig{});
    benchmark::DoNotOptimize(result.image.pixels.data());
    image = result.image;
  }
  Finish(state, batch, image);
}
BENCHMARK(BM_HashedReference)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace hpsf

BENCHMARK_MAIN();
