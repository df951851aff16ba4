#include "emulated/level_seed_kernel.h"

#include <bit>

#include "core/shared/level_seed.h"

namespace hpsf {

simt::KernelTask LevelSeedKernel(simt::ThreadContext& ctx, const LevelSeedArgs& args) {
  // Touch t: record t mod n at t / n levels above its own cell (core/shared/levels.h).
  const std::uint32_t t = ctx.Thread();
  const auto n = static_cast<std::uint32_t>(args.keys.size());
  const TableBuffers& b = args.buffers;
  const auto slot = static_cast<std::uint32_t>(co_await ctx.Load(b.placements, t));
  if (slot >= args.capacity || args.previous->counts[slot] != 0) co_return;  // not placed, or not new
  if (co_await ctx.AtomicCas(args.seeded, slot, 0, 1) != 0) co_return;       // another record seeds it
  const shared::KeyWords words = shared::CoarserKeyWords(args.keys[t % n].words, t / n);
  const CellState seed = SeedOf(words, args.level_seed, args.fixed, [&](const shared::KeyWords& w) {
    return FindInTable(*args.previous, w, args.normal_in_index);
  });
  if (seed.count == 0) co_return;
  for (int c = 0; c < 3; ++c) {
    const std::uint64_t index = std::uint64_t(slot) * 3 + c;
    if (args.fixed) {
      co_await ctx.AtomicAdd(b.sums, index, seed.fixed_sum[c]);
    } else {
      co_await ctx.AtomicAddFloat(b.sums, index, std::bit_cast<std::uint32_t>(seed.float_sum[c]));
    }
  }
  co_await ctx.AtomicAdd(b.counts, slot, seed.count);
  co_await ctx.Store(args.seeded, slot, 2);
  co_await ctx.AtomicAdd(args.seeded_count, 0, 1);
}

}  // namespace hpsf
