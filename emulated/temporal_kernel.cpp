#include "emulated/temporal_kernel.h"

#include <bit>

#include "core/shared/packed_sums.h"
#include "core/temporal.h"

namespace hpsf {
namespace {

// packed-decimal's count word holds the frame counter too (core/shared/packed_sums.h).
std::uint64_t CountOf(std::uint64_t word, bool packed) {
  return packed ? shared::PackedCount(std::uint32_t(word)) : word;
}

}  // namespace

simt::KernelTask TemporalKernel(simt::ThreadContext& ctx, const TemporalArgs& args) {
  const auto slot =
      args.list.on ? static_cast<std::uint32_t>(co_await ctx.Load(args.list.slots, ctx.Thread())) : ctx.Thread();
  const TableBuffers& b = args.buffers;
  const bool integer = IntegerSums(args.accumulation);
  const bool packed = args.accumulation == Accumulation::kPackedDecimal;
  CellState before, accumulated;
  const std::uint64_t old_word = co_await ctx.Load(args.previous_counts, slot);
  before.count = CountOf(old_word, packed);
  if (before.count == 0) co_return;  // a new cell, or none: nothing to blend
  const std::uint64_t new_word = co_await ctx.Load(b.counts, slot);
  if (new_word == old_word) co_return;  // the frame did not touch it
  accumulated.count = CountOf(new_word, packed);
  for (int c = 0; c < 3; ++c) {
    const std::uint64_t word = std::uint64_t(slot) * 3 + c;
    const std::uint64_t old_sum = co_await ctx.Load(args.previous_sums, word);
    const std::uint64_t new_sum = co_await ctx.Load(b.sums, word);
    before.fixed_sum[c] = old_sum;
    accumulated.fixed_sum[c] = new_sum;
    before.float_sum[c] = std::bit_cast<float>(std::uint32_t(old_sum));
    accumulated.float_sum[c] = std::bit_cast<float>(std::uint32_t(new_sum));
  }
  if (b.keeps_squares) {
    const std::uint64_t old_square = co_await ctx.Load(args.previous_squares, slot);
    const std::uint64_t new_square = co_await ctx.Load(b.squares, slot);
    before.fixed_square = old_square;
    accumulated.fixed_square = new_square;
    before.float_square = std::bit_cast<float>(std::uint32_t(old_square));
    accumulated.float_square = std::bit_cast<float>(std::uint32_t(new_square));
  }
  const CellState blended = BlendCellState(args.params, args.accumulation, before, accumulated);
  if (b.keeps_squares) {
    co_await ctx.Store(b.squares, slot,
                       integer ? blended.fixed_square : std::bit_cast<std::uint32_t>(blended.float_square));
  }
  for (int c = 0; c < 3; ++c) {
    const std::uint64_t word = integer ? blended.fixed_sum[c] : std::bit_cast<std::uint32_t>(blended.float_sum[c]);
    co_await ctx.Store(b.sums, std::uint64_t(slot) * 3 + c, word);
  }
  const std::uint64_t count =
      packed ? shared::PackCountWord(std::uint32_t(blended.count), shared::PackedFrames(std::uint32_t(new_word)))
             : blended.count;
  co_await ctx.Store(b.counts, slot, count);
}

}  // namespace hpsf
