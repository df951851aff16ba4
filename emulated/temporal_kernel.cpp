#include "emulated/temporal_kernel.h"

#include <bit>

#include "core/temporal.h"

namespace hpsf {

simt::KernelTask TemporalKernel(simt::ThreadContext& ctx, const TemporalArgs& args) {
  const auto slot =
      args.list.on ? static_cast<std::uint32_t>(co_await ctx.Load(args.list.slots, ctx.Thread())) : ctx.Thread();
  const TableBuffers& b = args.buffers;
  CellState before, accumulated;
  before.count = co_await ctx.Load(args.previous_counts, slot);
  if (before.count == 0) co_return;  // a new cell, or none: nothing to blend
  accumulated.count = co_await ctx.Load(b.counts, slot);
  if (accumulated.count == before.count) co_return;  // the frame did not touch it
  for (int c = 0; c < 3; ++c) {
    const std::uint64_t word = std::uint64_t(slot) * 3 + c;
    const std::uint64_t old_word = co_await ctx.Load(args.previous_sums, word);
    const std::uint64_t new_word = co_await ctx.Load(b.sums, word);
    before.fixed_sum[c] = old_word;
    accumulated.fixed_sum[c] = new_word;
    before.float_sum[c] = std::bit_cast<float>(std::uint32_t(old_word));
    accumulated.float_sum[c] = std::bit_cast<float>(std::uint32_t(new_word));
  }
  const CellState blended = BlendCellState(args.params, args.fixed, before, accumulated);
  for (int c = 0; c < 3; ++c) {
    const std::uint64_t word = args.fixed ? blended.fixed_sum[c] : std::bit_cast<std::uint32_t>(blended.float_sum[c]);
    co_await ctx.Store(b.sums, std::uint64_t(slot) * 3 + c, word);
  }
  co_await ctx.Store(b.counts, slot, blended.count);
}

}  // namespace hpsf
