#include "emulated/eviction_kernels.h"

#include <algorithm>

#include "core/hash_table.h"

namespace hpsf {

simt::KernelTask EvictKernel(simt::ThreadContext& ctx, const EvictionArgs& args) {
  const std::uint32_t slot = ctx.Thread();
  const TableBuffers& b = args.buffers;
  if (co_await ctx.Load(b.tags, slot) == kEmptyTag) co_return;
  if (co_await ctx.Load(b.counts, slot) == 0) co_return;  // a tombstone already
  const auto last_seen = static_cast<std::uint32_t>(co_await ctx.Load(b.last_seen, slot));
  if (!args.eviction.Evicts(args.frame, last_seen)) co_return;
  for (int c = 0; c < 3; ++c) co_await ctx.Store(b.sums, std::uint64_t(slot) * 3 + c, 0);
  co_await ctx.Store(b.counts, slot, 0);
  co_await ctx.AtomicAdd(args.evicted, 0, 1);
}

simt::KernelTask ReclaimKernel(simt::ThreadContext& ctx, const EvictionArgs& args) {
  const std::uint32_t slot = ctx.Thread();
  const TableBuffers& b = args.buffers;
  if (co_await ctx.Load(b.tags, slot) == kEmptyTag) co_return;
  if (co_await ctx.Load(b.counts, slot) != 0) co_return;  // live
  const std::uint32_t reach = std::min(args.probe_limit, args.capacity);
  for (std::uint32_t distance = 1; distance < reach; ++distance) {
    const std::uint32_t next = (slot + distance) & (args.capacity - 1u);
    if (co_await ctx.Load(b.tags, next) == kEmptyTag) break;
    if (co_await ctx.Load(b.counts, next) != 0) co_return;  // a live slot may have probed past this one: keep
  }
  co_await ctx.Store(b.tags, slot, kEmptyTag);
}

}  // namespace hpsf
