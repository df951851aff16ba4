// Compaction into a list of occupied slots (core/compaction.h), as emulator launches. Gather, one thread per record
// after the accumulate: a placed record whose slot's flag it is the first to set (a compare-and-swap from 0 to 1)
// appends the slot at the list's count (an atomic add). Prune, one thread per entry after the reclaim: an entry
// whose slot is still occupied is appended to the next list, one the reclaim emptied clears its flag; then one thread
// moves the next list's count to the list's, and the host takes the next list's entries as the list's (the buffers
// swap). The passes over slots launch one thread per entry (the count read back: the emulator's indirect dispatch)
// and step the entry's slot. The dump carries the list alone: the next frame sets the flags of its entries again,
// where a device keeps its flags from frame to frame.
#ifndef HPSF_EMULATED_COMPACTION_KERNELS_H
#define HPSF_EMULATED_COMPACTION_KERNELS_H

#include <cstdint>

#include "emulated/accumulate_kernel.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

// The list's buffers; `on` false: no compaction, a pass over slots launches one thread per slot.
struct OccupiedList {
  bool on = false;
  std::uint32_t listed = 0;      // 32-bit per slot: 1 while the slot is in the list
  std::uint32_t slots = 0;       // 32-bit, capacity entries: the list
  std::uint32_t count = 0;       // 64-bit, one word: the list's length
  std::uint32_t next_slots = 0;  // the prune's output, as slots
  std::uint32_t next_count = 0;  // and count
};

struct CompactionArgs {
  std::uint32_t capacity = 0;
  TableBuffers buffers{};
  OccupiedList list{};
};

simt::KernelTask GatherOccupiedKernel(simt::ThreadContext& ctx, const CompactionArgs& args);  // per record
simt::KernelTask PruneOccupiedKernel(simt::ThreadContext& ctx, const CompactionArgs& args);   // per entry
simt::KernelTask FinishPruneKernel(simt::ThreadContext& ctx, const CompactionArgs& args);     // one thread

}  // namespace hpsf

#endif  // HPSF_EMULATED_COMPACTION_KERNELS_H
