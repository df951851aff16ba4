#include "emulated/occupancy_kernels.h"

#include <algorithm>
#include <bit>
#include <memory>
#include <utility>
#include <vector>

namespace hpsf {

simt::KernelTask MarkOccupancyKernel(simt::ThreadContext& ctx, const OccupancyArgs& args) {
  const OccupancyTriangle& t = args.triangles[ctx.Thread()];
  const shared::FixedPoint3 v0 = shared::FixedVertex(args.grid, t[0]);
  const shared::FixedPoint3 v1 = shared::FixedVertex(args.grid, t[1]);
  const shared::FixedPoint3 v2 = shared::FixedVertex(args.grid, t[2]);
  const shared::CellRange r = shared::TriangleCellRange(v0, v1, v2, args.level, args.grid.resolution_log2);
  const int field_log2 = shared::OccupancyFieldLog2(args.grid.resolution_log2, args.level);
  for (int z = r.z0; z <= r.z1; ++z) {
    for (int y = r.y0; y <= r.y1; ++y) {
      for (int x = r.x0; x <= r.x1; ++x) {
        if (!shared::TriangleMeetsCell(v0, v1, v2, x, y, z, args.level)) continue;
        const std::uint32_t word = shared::OccupancyWord(x, y, z, field_log2);
        const std::uint32_t bit = 1u << shared::OccupancyBit(x, y, z);
        if (args.or_by_load_and_store) {
          const std::uint64_t old = co_await ctx.Load(args.words, word);
          co_await ctx.Store(args.words, word, old | bit);
        } else {
          co_await ctx.AtomicOr(args.words, word, bit);
        }
      }
    }
  }
}

simt::KernelTask CountOccupancyKernel(simt::ThreadContext& ctx, const OccupancyArgs& args) {
  std::uint64_t bits = 0;
  for (std::uint32_t w = ctx.Thread(); w < args.word_count; w += args.counting_threads) {
    bits += std::popcount(std::uint32_t(co_await ctx.Load(args.words, w)));
  }
  if (bits != 0) co_await ctx.AtomicAdd(args.count, 0, bits);
}

EmulatedOccupancy VoxelizeEmulated(const shared::OccupancyGrid& grid, std::span<const OccupancyTriangle> triangles,
                                   int level, const EmulatorOptions& options, bool or_by_load_and_store) {
  options.Validate();
  const OccupancyLevel empty(grid, level);
  simt::DeviceMemory memory;
  OccupancyArgs args;
  args.grid = grid;
  args.level = level;
  args.triangles = triangles;
  args.word_count = static_cast<std::uint32_t>(empty.words().size());
  args.words = memory.Allocate32("occupancy", args.word_count);
  args.count = memory.Allocate64("occupied", 1);
  args.counting_threads = std::min(args.word_count, kCountingThreads);
  args.or_by_load_and_store = or_by_load_and_store;
  EmulatedOccupancy result{empty, 0, {}};
  const auto launch = [&](std::uint32_t threads, simt::KernelTask (*kernel)(simt::ThreadContext&, const OccupancyArgs&),
                          const EmulatorOptions& how) {
    const simt::Kernel bound = [&](simt::ThreadContext& ctx) { return kernel(ctx, args); };
    if (how.mode == simt::Mode::kFast) {
      simt::LaunchFast(memory, threads, bound, how.threads);
      return simt::LaunchReport{};
    }
    const std::uint32_t warps = (threads + how.warp_size - 1) / how.warp_size;
    std::unique_ptr<simt::Schedule> parsed;
    if (!how.schedule_instance) parsed = simt::MakeSchedule(how.schedule, warps, std::uint64_t(warps) * 64);
    simt::Schedule& schedule = how.schedule_instance ? *how.schedule_instance : *parsed;
    return simt::LaunchFaithful(memory, threads, how.warp_size, bound, schedule);
  };
  result.marking = launch(static_cast<std::uint32_t>(triangles.size()), MarkOccupancyKernel, options);
  // The count by the same policy; under an exhaustive search, which drives the mark alone, round-robin.
  EmulatorOptions counting = options;
  if (counting.schedule_instance) {
    counting.schedule_instance = nullptr;
    counting.schedule = "round-robin";
  }
  launch(args.counting_threads, CountOccupancyKernel, counting);
  result.counted = std::as_const(memory).Words64(args.count)[0];  // before the take, which ends the memory's views
  result.field = OccupancyLevel(grid, level, memory.TakeWords32(args.words));
  return result;
}

}  // namespace hpsf
