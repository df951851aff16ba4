#include "emulated/compaction_kernels.h"

#include "core/hash_table.h"

namespace hpsf {

simt::KernelTask GatherOccupiedKernel(simt::ThreadContext& ctx, const CompactionArgs& args) {
  const auto slot = static_cast<std::uint32_t>(co_await ctx.Load(args.buffers.placements, ctx.Thread()));
  if (slot >= args.capacity) co_return;  // not placed
  // A plain read first: most records join a slot listed already, and a flag only goes from 0 to 1 in this pass.
  if (co_await ctx.Load(args.list.listed, slot) != 0) co_return;
  if (co_await ctx.AtomicCas(args.list.listed, slot, 0, 1) != 0) co_return;  // another record lists it
  const std::uint64_t entry = co_await ctx.AtomicAdd(args.list.count, 0, 1);
  co_await ctx.Store(args.list.slots, entry, slot);
}

simt::KernelTask PruneOccupiedKernel(simt::ThreadContext& ctx, const CompactionArgs& args) {
  const auto slot = static_cast<std::uint32_t>(co_await ctx.Load(args.list.slots, ctx.Thread()));
  if (co_await ctx.Load(args.buffers.tags, slot) == kEmptyTag) {
    co_await ctx.Store(args.list.listed, slot, 0);
    co_return;
  }
  const std::uint64_t entry = co_await ctx.AtomicAdd(args.list.next_count, 0, 1);
  co_await ctx.Store(args.list.next_slots, entry, slot);
}

simt::KernelTask FinishPruneKernel(simt::ThreadContext& ctx, const CompactionArgs& args) {
  co_await ctx.Store(args.list.count, 0, co_await ctx.Load(args.list.next_count, 0));
  co_await ctx.Store(args.list.next_count, 0, 0);
}

}  // namespace hpsf
