// The HashCache's occupancy (core/occupancy.h holds the reference's) as emulator launches, as occupancy.comp runs it on
// Vulkan: mark, one thread per triangle, tests every cell of its bounding box (core/shared/occupancy.h) and sets the
// bits of the cells it meets by atomic or; count adds the words' popcounts to the count, one atomic add a thread. The
// order of the ors cannot change a bit, so every schedule gives the reference's field; a mark that sets its bits by a
// load and a store (the broken variant) loses the bits another thread set in between, which the schedules find.
#ifndef HPSF_EMULATED_OCCUPANCY_KERNELS_H
#define HPSF_EMULATED_OCCUPANCY_KERNELS_H

#include <cstdint>
#include <span>

#include "core/occupancy.h"
#include "emulated/emulated_filter.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

struct OccupancyArgs {
  shared::OccupancyGrid grid{};
  int level = 0;
  std::span<const OccupancyTriangle> triangles;
  std::uint32_t words = 0;  // 32-bit: the field
  std::uint32_t word_count = 0;
  std::uint32_t count = 0;             // 64-bit, one word: the occupied cells
  std::uint32_t counting_threads = 1;  // the count's threads, each summing every counting_threads-th word
  bool or_by_load_and_store = false;   // the broken variant
};

simt::KernelTask MarkOccupancyKernel(simt::ThreadContext& ctx, const OccupancyArgs& args);  // per triangle
// The count launches at most kCountingThreads threads, as a device's grid-stride loop: a field has up to 2^25 words.
inline constexpr std::uint32_t kCountingThreads = 256;
simt::KernelTask CountOccupancyKernel(simt::ThreadContext& ctx, const OccupancyArgs& args);

struct EmulatedOccupancy {
  OccupancyLevel field;
  std::uint64_t counted = 0;   // the count launch's: the field's popcount
  simt::LaunchReport marking;  // faithful mode: the mark launch's trace
};

// The cells of `level` that the triangles meet, on the emulator in `options`' mode (its schedule, warp size, threads).
EmulatedOccupancy VoxelizeEmulated(const shared::OccupancyGrid& grid, std::span<const OccupancyTriangle> triangles,
                                   int level, const EmulatorOptions& options, bool or_by_load_and_store = false);

}  // namespace hpsf

#endif  // HPSF_EMULATED_OCCUPANCY_KERNELS_H
