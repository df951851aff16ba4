// packed-decimal's settle after a frame's accumulate (core/shared/packed_sums.h), as an emulator launch of one
// thread per slot, or per entry of the occupied list: a slot with samples advances its frame counter and is halved
// where its count or a sum passed the layout's bound. A pass of its own: a slot halved inside the accumulate would
// halve while other records still add to it.
#ifndef HPSF_EMULATED_PACKED_SETTLE_KERNEL_H
#define HPSF_EMULATED_PACKED_SETTLE_KERNEL_H

#include <cstdint>

#include "emulated/accumulate_kernel.h"
#include "emulated/compaction_kernels.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

struct PackedSettleArgs {
  TableBuffers buffers{};    // 32-bit sums and count words
  std::uint32_t halved = 0;  // 64-bit, one word: the slots halved
  OccupiedList list{};       // with compaction: one thread per entry
};

simt::KernelTask PackedSettleKernel(simt::ThreadContext& ctx, const PackedSettleArgs& args);

}  // namespace hpsf

#endif  // HPSF_EMULATED_PACKED_SETTLE_KERNEL_H
