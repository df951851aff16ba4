// The HashCache's occupancy of the Cornell box's triangles at 2^7 to 2^9 finest cells per axis: the reference's
// voxelization (one core), the emulator's fast mode (all cores) and occupancy.comp on the Vulkan device, each a whole
// call (Vulkan's includes its pipeline, buffers, upload and read-back of the field), and the reference's coarsening of
// the finest level into the rest of the octree. Run:
//   build/default/bin/occupancy_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <vector>

#include <benchmark/benchmark.h>

#include "core/occupancy.h"
#include "emulated/occupancy_kernels.h"
#include "tools/benchmarks/benchmark_vulkan.h"
#include "tracer/scene_file.h"
#include "vulkan/occupancy_pass.h"

namespace hpsf {
namespace {

const std::vector<OccupancyTriangle>& Cornell() {
  static const std::vector<OccupancyTriangle> triangles = [] {
    std::vector<OccupancyTriangle> t;
    for (const Triangle& tri : LoadScene("cornell").triangles) t.push_back({tri.p0, tri.p1, tri.p2});
    return t;
  }();
  return triangles;
}

void Report(benchmark::State& state, const OccupancyLevel& field) {
  state.counters["occupied"] = double(field.Count());
  state.counters["triangles"] = double(Cornell().size());
}

void BM_OccupancyReference(benchmark::State& state) {
  const shared::OccupancyGrid grid = GridOver(Cornell(), int(state.range(0)), "cornell");
  for (auto _ : state) benchmark::DoNotOptimize(VoxelizeTriangles(grid, Cornell()).words().data());
  Report(state, VoxelizeTriangles(grid, Cornell()));
}
BENCHMARK(BM_OccupancyReference)->DenseRange(7, 9)->Unit(benchmark::kMillisecond);

void BM_OccupancyEmulatorFast(benchmark::State& state) {
  const shared::OccupancyGrid grid = GridOver(Cornell(), int(state.range(0)), "cornell");
  for (auto _ : state) benchmark::DoNotOptimize(VoxelizeEmulated(grid, Cornell(), 0, EmulatorOptions{}).counted);
  Report(state, VoxelizeTriangles(grid, Cornell()));
}
BENCHMARK(BM_OccupancyEmulatorFast)->DenseRange(7, 9)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OccupancyVulkan(benchmark::State& state) {
  VulkanDevice* device = benchmarks::Device(state, StagingPolicy::kAuto);
  if (!device) return;
  const shared::OccupancyGrid grid = GridOver(Cornell(), int(state.range(0)), "cornell");
  for (auto _ : state) benchmark::DoNotOptimize(VoxelizeOnDevice(*device, grid, Cornell()).counted);
  Report(state, VoxelizeTriangles(grid, Cornell()));
  state.SetLabel(device->info().name);
}
BENCHMARK(BM_OccupancyVulkan)->DenseRange(7, 9)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OccupancyCoarsening(benchmark::State& state) {
  const shared::OccupancyGrid grid = GridOver(Cornell(), int(state.range(0)), "cornell");
  const OccupancyLevel finest = VoxelizeTriangles(grid, Cornell());
  for (auto _ : state) {
    OccupancyLevel level = finest;
    while (level.level() < grid.resolution_log2) level = Coarsened(level);
    benchmark::DoNotOptimize(level.words().data());
  }
  Report(state, finest);
}
BENCHMARK(BM_OccupancyCoarsening)->DenseRange(7, 9)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hpsf

HPSF_BENCHMARK_MAIN();
