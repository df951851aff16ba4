#include "emulated/eviction_kernels.h"

#include <algorithm>

#include "core/hash_table.h"
#include "core/shared/eviction_priority.h"
#include "core/shared/packed_sums.h"

namespace hpsf {

simt::KernelTask SelectVictimsKernel(simt::ThreadContext& ctx, const EvictionArgs& args) {
  // Touch t: record t mod n at t / n levels above its own cell (core/shared/levels.h).
  const std::uint32_t t = ctx.Thread();
  const auto n = static_cast<std::uint32_t>(args.keys.size());
  const TableBuffers& b = args.buffers;
  if (co_await ctx.Load(b.placements, t) != kProbeFailure) co_return;
  const KeyResult& own = args.keys[t % n];
  const std::uint32_t slot0 =
      t < n ? own.slot0 : shared::Slot0AtLevel(own.words, t / n, args.normal_in_index ? 1u : 0u, args.capacity - 1u);
  bool found = false;
  std::uint32_t victim = 0;
  SlotTag victim_tag = 0;
  std::uint64_t victim_priority = 0;
  const shared::ProbeScheme scheme = args.scheme();
  for (std::uint32_t probe = 0; probe < args.probe_limit; ++probe) {
    const std::uint32_t slot = shared::CandidateSlot(scheme, slot0, probe);
    const SlotTag tag = co_await ctx.Load(b.tags, slot);
    if (tag == kEmptyTag || tag == shared::kTombstoneTag) continue;
    const std::uint64_t word = co_await ctx.Load(b.counts, slot);
    const std::uint64_t count = args.packed_counts ? shared::PackedCount(std::uint32_t(word)) : word;
    const auto last_seen = static_cast<std::uint32_t>(co_await ctx.Load(b.last_seen, slot));
    if (count == 0 || last_seen == args.frame) continue;  // a tombstone of another policy, or touched this frame
    const std::uint64_t priority = shared::EvictionPriority(last_seen, count);
    if (!found || shared::EvictedBefore(priority, tag, victim_priority, victim_tag)) {
      found = true;
      victim = slot;
      victim_priority = priority;
      victim_tag = tag;
    }
  }
  if (found) co_await ctx.Store(args.victims, victim, 1);
}

simt::KernelTask EvictKernel(simt::ThreadContext& ctx, const EvictionArgs& args) {
  const auto slot =
      args.list.on ? static_cast<std::uint32_t>(co_await ctx.Load(args.list.slots, ctx.Thread())) : ctx.Thread();
  const TableBuffers& b = args.buffers;
  if (co_await ctx.Load(b.tags, slot) == kEmptyTag) co_return;
  if (co_await ctx.Load(b.counts, slot) == 0) co_return;  // a tombstone already
  if (args.eviction.by_priority()) {
    if (co_await ctx.Load(args.victims, slot) == 0) co_return;
  } else {
    const auto last_seen = static_cast<std::uint32_t>(co_await ctx.Load(b.last_seen, slot));
    if (!args.eviction.Evicts(args.frame, last_seen)) co_return;
  }
  for (int c = 0; c < 3; ++c) co_await ctx.Store(b.sums, std::uint64_t(slot) * 3 + c, 0);
  if (b.keeps_squares) co_await ctx.Store(b.squares, slot, 0);
  co_await ctx.Store(b.counts, slot, 0);
  if (args.eviction.by_priority()) co_await ctx.Store(b.tags, slot, shared::kTombstoneTag);
  co_await ctx.AtomicAdd(args.evicted, 0, 1);
}

simt::KernelTask ReclaimKernel(simt::ThreadContext& ctx, const EvictionArgs& args) {
  const auto slot =
      args.list.on ? static_cast<std::uint32_t>(co_await ctx.Load(args.list.slots, ctx.Thread())) : ctx.Thread();
  const TableBuffers& b = args.buffers;
  if (co_await ctx.Load(b.tags, slot) == kEmptyTag) co_return;
  if (co_await ctx.Load(b.counts, slot) != 0) co_return;  // live
  const shared::ProbeScheme scheme = args.scheme();
  for (std::uint32_t distance = 1;; ++distance) {
    const std::uint32_t next = shared::SlotAfter(scheme, slot, distance);
    if (next == shared::kNoCandidate) break;
    if (co_await ctx.Load(b.tags, next) == kEmptyTag) break;
    if (co_await ctx.Load(b.counts, next) != 0) co_return;  // a live slot may have probed past this one: keep
  }
  co_await ctx.Store(b.tags, slot, kEmptyTag);
}

}  // namespace hpsf
