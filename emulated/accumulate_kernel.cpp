#include "emulated/accumulate_kernel.h"

#include <bit>

#include "core/hash_table.h"
#include "core/shared/eviction_priority.h"
#include "core/shared/fixed_point.h"
#include "core/shared/levels.h"
#include "core/shared/second_moment.h"

namespace hpsf {

KeyResult KeyOfLevel(const AccumulateArgs& args, std::uint32_t record, std::uint32_t level) {
  return shared::KeyAtLevel(args.key_params, args.keys[record], level);
}

simt::KernelTask AccumulateKernel(simt::ThreadContext& ctx, const AccumulateArgs& args) {
  return AccumulateLevels(ctx, args, KeyOfLevel);
}

simt::KernelTask AccumulateLevels(simt::ThreadContext& ctx, const AccumulateArgs& args, LevelKeyFn key_of_level) {
  const std::uint32_t i = ctx.Thread();
  const TableBuffers& b = args.buffers;
  const std::uint32_t n = static_cast<std::uint32_t>(args.keys.size());
  // Each of the record's levels in turn, its own first (core/shared/levels.h).
  for (std::uint32_t k = 0; k < args.levels; ++k) {
    const KeyResult key = key_of_level(args, i, k);
    const std::uint32_t placement = shared::LevelPlacementIndex(i, k, n);
    if (!args.accepted[i] || key.status != shared::kKeyed) {
      co_await ctx.Store(b.placements, placement, kNotPlaced);
      continue;
    }
    const Record& r = args.records[i];
    const SlotTag identity = StoredIdentity(key);
    const shared::ProbeScheme scheme = args.scheme();
    std::uint32_t slot = kProbeFailure;
    if (args.claim_tombstones) {
      // Priority eviction's tombstones may be claimed, so the cell may lie past one: look for it first, up to the
      // first empty slot (no live cell lies past a hole, D7) ...
      for (std::uint32_t probe = 0; probe < args.probe_limit && slot == kProbeFailure; ++probe) {
        const std::uint32_t s = shared::CandidateSlot(scheme, key.slot0, probe);
        const std::uint64_t tag = co_await ctx.Load(b.tags, s);
        if (tag == identity) slot = s;
        if (tag == kEmptyTag) break;
      }
      // ... then claim the first empty or tombstone slot; one that another record of this cell claimed meanwhile
      // is joined. Claimable slots only get fewer during the pass, so every record of a cell ends in the same slot.
      for (std::uint32_t probe = 0; probe < args.probe_limit && slot == kProbeFailure; ++probe) {
        const std::uint32_t s = shared::CandidateSlot(scheme, key.slot0, probe);
        std::uint64_t tag = co_await ctx.Load(b.tags, s);
        if (tag == kEmptyTag || tag == shared::kTombstoneTag) {
          const std::uint64_t seen = co_await ctx.AtomicCas(b.tags, s, tag, identity);
          tag = seen == tag ? identity : seen;
        }
        if (tag == identity) slot = s;
      }
    } else {
      for (std::uint32_t probe = 0; probe < args.probe_limit && slot == kProbeFailure; ++probe) {
        const std::uint32_t s = shared::CandidateSlot(scheme, key.slot0, probe);
        std::uint64_t tag = co_await ctx.Load(b.tags, s);
        if (tag == kEmptyTag) tag = co_await ctx.AtomicCas(b.tags, s, kEmptyTag, identity);
        // An empty slot we just claimed (CAS returned 0) or a slot that holds our identity: add here, once.
        if (tag == kEmptyTag || tag == identity) slot = s;
      }
    }
    if (slot == kProbeFailure) {
      co_await ctx.Store(b.placements, placement, kProbeFailure);
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      if (IntegerSums(args.accumulation)) {
        const std::uint64_t add = shared::ToFixedPoint(r.contribution[c], args.fixed_point_scale);
        const std::uint64_t old = co_await ctx.AtomicAdd(b.sums, std::uint64_t(slot) * 3 + c, add);
        if (SumAddWrapped(args.accumulation, old, add)) co_await ctx.AtomicAdd(b.wraps, 0, 1);
      } else {
        co_await ctx.AtomicAddFloat(b.sums, std::uint64_t(slot) * 3 + c,
                                    std::bit_cast<std::uint32_t>(r.contribution[c]));
      }
    }
    if (b.keeps_squares && IntegerSums(args.accumulation)) {
      const std::uint64_t add = shared::SquareToFixedPoint(glm::vec3(r.contribution), args.square_scale);
      const std::uint64_t old = co_await ctx.AtomicAdd(b.squares, slot, add);
      if (SumAddWrapped(args.accumulation, old, add)) co_await ctx.AtomicAdd(b.wraps, 0, 1);
    } else if (b.keeps_squares) {
      co_await ctx.AtomicAddFloat(b.squares, slot,
                                  std::bit_cast<std::uint32_t>(shared::SquareAsFloat(glm::vec3(r.contribution))));
    }
    // A count of 2^64 - 1 wraps to 0 (D12): no frame sequence gets there, but a table loaded with one can.
    // packed-decimal's count word adds 1 too; its 24-bit count carries into the frame counter at 2^24.
    if (CountAddWrapped(args.accumulation, co_await ctx.AtomicAdd(b.counts, slot, 1)))
      co_await ctx.AtomicAdd(b.wraps, 1, 1);
    if (args.track_last_seen) co_await ctx.Store(b.last_seen, slot, args.frame);
    co_await ctx.Store(b.placements, placement, slot);
  }
}

void PrefetchAccumulate(const simt::DeviceMemory& memory, const AccumulateArgs& args, std::uint32_t i) {
  const std::uint32_t slot = shared::FirstCandidate(args.scheme(), args.keys[i].slot0);
  const TableBuffers& b = args.buffers;
  memory.Prefetch({b.tags, slot});
  memory.Prefetch({b.sums, std::uint64_t(slot) * 3});
  memory.Prefetch({b.sums, std::uint64_t(slot) * 3 + 2});  // the three sums may straddle two lines
  memory.Prefetch({b.counts, slot});
  if (args.track_last_seen) memory.Prefetch({b.last_seen, slot});
}

}  // namespace hpsf
