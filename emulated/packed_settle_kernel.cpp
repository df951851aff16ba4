#include "emulated/packed_settle_kernel.h"

#include "core/shared/packed_sums.h"

namespace hpsf {

simt::KernelTask PackedSettleKernel(simt::ThreadContext& ctx, const PackedSettleArgs& args) {
  const auto slot =
      args.list.on ? static_cast<std::uint32_t>(co_await ctx.Load(args.list.slots, ctx.Thread())) : ctx.Thread();
  const TableBuffers& b = args.buffers;
  const auto word = static_cast<std::uint32_t>(co_await ctx.Load(b.counts, slot));
  if (shared::PackedCount(word) == 0) co_return;  // empty, or a tombstone
  glm::uvec4 cell(0u, 0u, 0u, word);
  for (int c = 0; c < 3; ++c)
    cell[c] = static_cast<std::uint32_t>(co_await ctx.Load(b.sums, std::uint64_t(slot) * 3 + c));
  const bool halving = shared::PackedNeedsHalving(cell);
  const glm::uvec4 settled = shared::SettlePacked(cell);
  if (halving) {
    for (int c = 0; c < 3; ++c) co_await ctx.Store(b.sums, std::uint64_t(slot) * 3 + c, settled[c]);
    co_await ctx.AtomicAdd(args.halved, 0, 1);
  }
  co_await ctx.Store(b.counts, slot, settled.w);
}

}  // namespace hpsf
