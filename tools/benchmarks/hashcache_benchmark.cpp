// The HashCache on the Cornell box at 2^8 finest cells per axis, one frame of cache samples traced at 1 spp with
// l_store = l_len = 3 (about three samples a pixel) at 16:9 sizes up to 1080p: the construction (every level's
// occupancy and cuckoo map, the reference's), a frame's update by sort and reduce and by atomics on each backend (the
// emulator's fast mode on all cores up to 480x270: its sort is a launch per bitonic step; lavapipe's sort and reduce up
// to 960x540), and the reference's
// reconstruction of the frame's primary hits. Each update starts from the same cache (copied outside the timing);
// Vulkan's includes its uploads and read-backs. Counters: samples, the levels' slots, and the hash and data memory.
// Run:
//   build/default/bin/hashcache_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <map>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "core/fixed_point_scale.h"
#include "core/footprint.h"
#include "core/hashcache_reconstruct.h"
#include "core/hashcache_update.h"
#include "emulated/hashcache_update_kernels.h"
#include "tools/benchmarks/benchmark_vulkan.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "vulkan/hashcache_update_pass.h"

namespace hpsf {
namespace {

constexpr int kResolutionLog2 = 8;

const Scene& Cornell() {
  static const Scene scene = LoadScene("cornell");
  return scene;
}

std::vector<OccupancyTriangle> Triangles() {
  std::vector<OccupancyTriangle> t;
  for (const Triangle& tri : Cornell().triangles) t.push_back({tri.p0, tri.p1, tri.p2});
  return t;
}

TraceOptions Frame(int height) {
  TraceOptions trace;
  trace.height = std::uint32_t(height);
  trace.width = trace.height * 16 / 9;
  trace.samples_per_pixel = 1;
  return trace;
}

const std::vector<HashCacheSample>& Samples(int height) {
  static std::map<int, std::vector<HashCacheSample>> traced;
  auto it = traced.find(height);
  if (it == traced.end()) {
    const PreparedScene prepared(Cornell(), 0);
    it = traced.emplace(height, TraceCacheSamples(prepared, Frame(height), {3, 3}).samples).first;
  }
  return it->second;
}

HashCache EmptyCache(HashCacheUpdateRule rule, int height) {
  const std::vector<OccupancyTriangle> triangles = Triangles();
  const shared::OccupancyGrid grid = GridOver(triangles, kResolutionLog2, "cornell");
  std::vector<CuckooMap> maps;
  for (const OccupancyLevel& level : OccupancyPyramid(grid, triangles)) {
    maps.push_back(BuildCuckooMap(OccupiedKeys(level), {.level = std::uint32_t(level.level())}).map);
  }
  std::vector<glm::vec3> lights;
  for (const HashCacheSample& s : Samples(height)) lights.push_back(s.light);
  return EmptyHashCache(grid, std::move(maps), Accumulation::kFixed64, ChooseFixedPointBitsOf(lights, {}, 64), 0, rule);
}

void Report(benchmark::State& state, const HashCache& cache, int height) {
  double slots = 0;
  for (const HashCacheLevel& level : cache.levels) slots += double(level.map.slots.size());
  state.counters["samples"] = double(Samples(height).size());
  state.counters["slots"] = slots;
  state.counters["hash_MiB"] = 4.0 * slots / double(1 << 20);
  // fixed64: a front, six 64-bit sums, two 64-bit counts and the wipe frame a slot.
  state.counters["data_MiB"] = (4.0 + 48.0 + 16.0 + 4.0) * slots / double(1 << 20);
}

void BM_HashCacheConstruction(benchmark::State& state) {
  const std::vector<OccupancyTriangle> triangles = Triangles();
  const shared::OccupancyGrid grid = GridOver(triangles, int(state.range(0)), "cornell");
  for (auto _ : state) {
    for (const OccupancyLevel& level : OccupancyPyramid(grid, triangles)) {
      benchmark::DoNotOptimize(BuildCuckooMap(OccupiedKeys(level), {.level = std::uint32_t(level.level())}).built);
    }
  }
}
BENCHMARK(BM_HashCacheConstruction)->DenseRange(7, 9)->Unit(benchmark::kMillisecond);

template <typename Update>
void RunUpdate(benchmark::State& state, HashCacheUpdateRule rule, Update update) {
  const int height = int(state.range(0));
  const HashCache empty = EmptyCache(rule, height);
  for (auto _ : state) {
    state.PauseTiming();
    HashCache cache = empty;
    state.ResumeTiming();
    update(cache, Samples(height));
    benchmark::DoNotOptimize(cache.levels[0].data.counts.data());
  }
  Report(state, empty, height);
}

void BM_HashCacheUpdateReference(benchmark::State& state) {
  RunUpdate(state, HashCacheUpdateRule(state.range(1)),
            [](HashCache& cache, std::span<const HashCacheSample> s) { UpdateHashCache(cache, s); });
}
BENCHMARK(BM_HashCacheUpdateReference)
    ->ArgsProduct({{135, 270, 540, 1080}, {0, 1}})
    ->ArgNames({"height", "atomics"})
    ->Unit(benchmark::kMillisecond);

void BM_HashCacheUpdateEmulatorFast(benchmark::State& state) {
  RunUpdate(state, HashCacheUpdateRule(state.range(1)), [](HashCache& cache, std::span<const HashCacheSample> s) {
    UpdateHashCacheEmulated(cache, s, EmulatorOptions{});
  });
}
BENCHMARK(BM_HashCacheUpdateEmulatorFast)
    ->ArgsProduct({{135, 270}, {0, 1}})
    ->ArgNames({"height", "atomics"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_HashCacheUpdateVulkan(benchmark::State& state) {
  VulkanDevice* device = benchmarks::Device(state, StagingPolicy::kAuto);
  if (!device) return;
  HashCacheUpdatePass pass(*device);
  RunUpdate(state, HashCacheUpdateRule(state.range(1)),
            [&](HashCache& cache, std::span<const HashCacheSample> s) { pass.Run(cache, s); });
  state.SetLabel(device->info().name);
}
// lavapipe's bitonic sort of 1080p's 6.2 million samples would take minutes: sort and reduce up to 540 rows.
BENCHMARK(BM_HashCacheUpdateVulkan)
    ->ArgsProduct({{135, 270, 540}, {0, 1}})
    ->Args({1080, 1})
    ->ArgNames({"height", "atomics"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The primary hits of the frame reconstructed from the cache after the frame's update: the lookups, the fill and the
// pixel means (one core).
void BM_HashCacheReconstruction(benchmark::State& state) {
  const int height = int(state.range(0));
  HashCache cache = EmptyCache(HashCacheUpdateRule::kSortAndReduce, height);
  UpdateHashCache(cache, Samples(height));
  TraceOptions trace = Frame(height);
  trace.max_depth = 1;
  const PreparedScene prepared(Cornell(), 0);
  const RecordBatch primary = TraceRecords(prepared, trace).batch;
  const shared::HashCacheLookupParams params{cache.grid, FootprintScale(4.0, primary.fov_y_radians, trace.height), 1.0f,
                                             1, 0};
  double filled = 0.0;
  for (auto _ : state) filled = ReconstructHashCache(cache, primary, params).FilledFraction();
  state.counters["pixels"] = double(trace.width) * trace.height;
  state.counters["filled"] = filled;
  state.counters["per_pixel"] = benchmark::Counter(
      double(trace.width) * trace.height, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_HashCacheReconstruction)->Arg(135)->Arg(540)->Arg(1080)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hpsf

BENCHMARK_MAIN();
