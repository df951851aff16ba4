// The temporal blend after a frame's accumulate (core/temporal.h), as an emulator launch of one thread per slot:
// a slot that held samples before the frame (its count in the previous table, the double buffer of Meijer §4.2.2
// and Schipek §5.3) and that the frame added to is blended by core's BlendCellState; every other slot keeps what
// it holds. packed-decimal's count word holds the cell's frame counter too, which the blend keeps (the settle after
// it advances the counter). The accumulate writes only the current table and the blend reads the previous one, which no
// pass of the frame writes: the averages are never read while they are being accumulated (docs/design/defects.md, D10).
#ifndef HPSF_EMULATED_TEMPORAL_KERNEL_H
#define HPSF_EMULATED_TEMPORAL_KERNEL_H

#include <cstdint>

#include "core/accumulation.h"
#include "core/shared/temporal_blend.h"
#include "emulated/accumulate_kernel.h"
#include "emulated/compaction_kernels.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

struct TemporalArgs {
  std::uint32_t capacity = 0;
  Accumulation accumulation = Accumulation::kFixed64;
  shared::TemporalParams params{};
  TableBuffers buffers{};              // the current table: sums and counts
  std::uint32_t previous_sums = 0;     // the table before the frame, laid out as buffers.sums
  std::uint32_t previous_counts = 0;   // and buffers.counts
  std::uint32_t previous_squares = 0;  // and buffers.squares, where it keeps them
  OccupiedList list{};                 // with compaction: one thread per entry
};

simt::KernelTask TemporalKernel(simt::ThreadContext& ctx, const TemporalArgs& args);

}  // namespace hpsf

#endif  // HPSF_EMULATED_TEMPORAL_KERNEL_H
