// The eviction pass after a frame's accumulate (core/eviction.h), as two emulator launches of one thread per slot.
// Evict: a live slot the policy evicts keeps its tag and becomes a tombstone (count and sums zeroed). Reclaim: a
// tombstone becomes empty (tag 0) unless a live slot lies after it within probe_limit - 1 slots with no empty slot
// between: such a live slot may have been placed by probing past the tombstone, and a hole there would make its
// key claim the hole next frame and split its cell (DESIGN.md D7).
//
// Tombstones, not compaction or rehashing: backward-shift compaction needs each slot's home (slot0), and a
// rehash the full key, neither of which the table stores; a tombstone needs nothing new and no slot moves, so
// every placement of the frame stays valid. The reclaim's threads race benignly: a thread that finds a
// neighbour already reclaimed reaches the decision it would have reached from the snapshot, because that
// neighbour found no live slot within a reach that covers the rest of this thread's.
#ifndef HPSF_EMULATED_EVICTION_KERNELS_H
#define HPSF_EMULATED_EVICTION_KERNELS_H

#include <cstdint>

#include "core/eviction.h"
#include "emulated/accumulate_kernel.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

struct EvictionArgs {
  std::uint32_t capacity = 0;
  std::uint32_t probe_limit = 0;
  std::uint32_t frame = 0;
  Eviction eviction;
  TableBuffers buffers{};
  std::uint32_t evicted = 0;  // 64-bit, one word: slots made tombstones
};

simt::KernelTask EvictKernel(simt::ThreadContext& ctx, const EvictionArgs& args);
simt::KernelTask ReclaimKernel(simt::ThreadContext& ctx, const EvictionArgs& args);

// The reclaim kernel to run; the D7 variant (emulated/defect_injection.h) empties every tombstone.
using ReclaimKernelFn = simt::KernelTask (*)(simt::ThreadContext&, const EvictionArgs&);

}  // namespace hpsf

#endif  // HPSF_EMULATED_EVICTION_KERNELS_H
