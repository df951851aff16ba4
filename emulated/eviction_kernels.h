// The eviction pass after a frame's accumulate (core/eviction.h), as two emulator launches of one thread per slot.
// Evict: a live slot the policy evicts keeps its tag and becomes a tombstone (count and sums zeroed). Reclaim: a
// tombstone becomes empty (tag 0) unless a live slot lies after it in some key's candidate order (within
// probe_limit - 1 slots, and in its bucket under bucket:B) with no empty slot between: such a live slot may have been
// placed by probing past the tombstone, and a hole there would make its key claim the hole next frame and split its
// cell (docs/design/defects.md, D7).
//
// Tombstones, not compaction or rehashing: backward-shift compaction needs each slot's home (slot0), and a
// rehash the full key, neither of which the table stores; a tombstone needs nothing new and no slot moves, so
// every placement of the frame stays valid. The reclaim's threads race benignly: a thread that finds a
// neighbour already reclaimed reaches the decision it would have reached from the snapshot, because that
// neighbour found no live slot within a reach that covers the rest of this thread's.
//
// Priority eviction (core/eviction.h) adds a launch before them, one thread per record: SelectVictims, in the
// window of each record that found no slot, marks the untouched live slot of lowest priority
// (core/shared/eviction_priority.h). The table is only read there, so the victims are a function of the state
// after the accumulate, whatever the order of the threads, and two failed records with one slot0 mark the same
// victim (overlapping windows may mark two). Evict then evicts the marked slots and tags them kTombstoneTag, which an
// insertion may claim.
#ifndef HPSF_EMULATED_EVICTION_KERNELS_H
#define HPSF_EMULATED_EVICTION_KERNELS_H

#include <cstdint>
#include <span>

#include "core/eviction.h"
#include "emulated/accumulate_kernel.h"
#include "emulated/compaction_kernels.h"
#include "emulated/simt/kernel_task.h"

namespace hpsf {

struct EvictionArgs {
  std::uint32_t capacity = 0;
  std::uint32_t probe_limit = 0;
  ProbeKind probing = ProbeKind::kLinear;
  std::uint32_t frame = 0;
  Eviction eviction;
  TableBuffers buffers{};
  std::uint32_t evicted = 0;  // 64-bit, one word: slots made tombstones
  // With priority: the frame's keys (slot0 per record) and a 32-bit mark per slot, 1 for a victim.
  std::span<const KeyResult> keys;
  std::uint32_t victims = 0;
  OccupiedList list{};  // with compaction: evict and reclaim launch one thread per entry
  // packed-decimal: the counts are count words (core/shared/packed_sums.h), whose count bits the priority reads.
  bool packed_counts = false;
  // --levels (core/shared/levels.h): the selection runs per touch, a coarser one's window from its derived slot0.
  std::uint32_t levels = 1;
  bool normal_in_index = true;
  shared::ProbeScheme scheme() const { return MakeProbeScheme(probing, capacity, probe_limit); }
};

simt::KernelTask SelectVictimsKernel(simt::ThreadContext& ctx, const EvictionArgs& args);  // per record and level
simt::KernelTask EvictKernel(simt::ThreadContext& ctx, const EvictionArgs& args);          // per slot
simt::KernelTask ReclaimKernel(simt::ThreadContext& ctx, const EvictionArgs& args);        // per slot

using EvictionKernelFn = simt::KernelTask (*)(simt::ThreadContext&, const EvictionArgs&);

// The eviction kernels to run where a variant may replace one (emulated/defect_injection.h): D7's reclaim empties
// every tombstone; the wrong-sign selection evicts the highest priority. A reclaim kernel converts, so a call that
// names only the reclaim keeps working.
// With compaction, the prune's last step may be replaced too: Bevy #21904's count of one with nothing listed.
struct EvictionKernels {
  using FinishPruneFn = simt::KernelTask (*)(simt::ThreadContext&, const CompactionArgs&);
  EvictionKernels(EvictionKernelFn reclaim_kernel = ReclaimKernel, EvictionKernelFn select_kernel = SelectVictimsKernel,
                  FinishPruneFn finish_prune_kernel = FinishPruneKernel)
      : reclaim(reclaim_kernel), select(select_kernel), finish_prune(finish_prune_kernel) {}
  EvictionKernelFn reclaim;
  EvictionKernelFn select;
  FinishPruneFn finish_prune;
};

}  // namespace hpsf

#endif  // HPSF_EMULATED_EVICTION_KERNELS_H
