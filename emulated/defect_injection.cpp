#include "emulated/defect_injection.h"

#include <algorithm>
#include <bit>

#include "core/cell_moments.h"
#include "core/error.h"
#include "core/hash_table.h"
#include "core/neighbour_search.h"
#include "core/shared/eviction_priority.h"
#include "core/shared/fixed_point.h"
#include "core/shared/levels.h"
#include "core/shared/lookup.h"
#include "core/shared/packed_sums.h"
#include "core/shared/second_moment.h"
#include "core/shared/transport.h"
#include "core/survival.h"
#include "core/temporal.h"
#include "core/transport.h"
#include "emulated/broken_survival.h"
#include "emulated/broken_transport.h"
#include "emulated/temporal_kernel.h"

namespace hpsf {
namespace {

// Changes of the correct kernel that are not Defect values: count32 is D12's, which needs a sequence of frames
// (D12Count32Bit); blend_in_pass D10's (D10BlendDuringAccumulate); evict_in_pass EvictDuringAccumulate's; weak_claim
// the correct claim by a weak compare-and-swap (AccumulateWithWeakCas); transport_in_pass TransportDuringAccumulate's;
// survival_in_pass SurvivalDuringAccumulate's.
struct Switches {
  bool count32 = false;
  bool blend_in_pass = false;
  bool evict_in_pass = false;
  bool weak_claim = false;
  bool transport_in_pass = false;
  bool survival_in_pass = false;
};

// The correct kernel (emulated/accumulate_kernel.cpp) with exactly one defect or switch in, in both modes.
simt::KernelTask Mutant(simt::ThreadContext& ctx, const AccumulateArgs& args, Defect defect, Switches switches = {}) {
  const auto [count32, blend_in_pass, evict_in_pass, weak_claim, transport_in_pass, survival_in_pass] = switches;
  const std::uint32_t i = ctx.Thread();
  const KeyResult& key = args.keys[i];
  const TableBuffers& b = args.buffers;
  const bool packed = args.accumulation == Accumulation::kPackedDecimal;
  glm::vec3 contribution(args.records[i].contribution);
  if (transport_in_pass && args.transport) {
    // The record's transport (core/transport.h) looked up in the table this pass is adding to, not the one before
    // the frame: what it reads depends on which adds of the frame came first.
    const TransportInPassArgs& t = *args.transport;
    const KeyResult& scattered = t.scattered_keys[i];
    std::uint32_t read = kNothingTransported;
    std::uint64_t count = 0;
    if (scattered.status == shared::kKeyed) {
      const shared::ProbeScheme scheme = args.scheme();
      for (std::uint32_t probe = 0; probe < args.probe_limit; ++probe) {
        const std::uint32_t s = shared::CandidateSlot(scheme, scattered.slot0, probe);
        const std::uint64_t tag = co_await ctx.Load(b.tags, s);
        const std::uint64_t word = co_await ctx.Load(b.counts, s);
        count = packed ? shared::PackedCount(std::uint32_t(word)) : word;
        const std::uint32_t step = shared::LookupStep(tag, StoredIdentity(scattered), count);
        if (step == shared::kLookupEnd) break;
        if (step == shared::kLookupFound) {
          read = s;
          break;
        }
      }
    }
    if (read != kNothingTransported) {
      std::array<std::uint64_t, 3> fixed_sum{};
      std::array<float, 3> float_sum{};
      for (int c = 0; c < 3; ++c) {
        fixed_sum[c] = co_await ctx.Load(b.sums, std::uint64_t(read) * 3 + c);
        float_sum[c] = std::bit_cast<float>(std::uint32_t(fixed_sum[c]));
      }
      StencilTotal cell;
      cell.Add(fixed_sum, float_sum, count);
      contribution = shared::TransportedContribution(contribution, glm::vec3(t.scattered[i].throughput),
                                                     cell.Average(args.accumulation, t.fixed_point_bits));
    }
    co_await ctx.Store(t.reads, i, read);
  }
  if (survival_in_pass && args.survival && i < args.survival->traced.size() && args.accepted[i] &&
      key.status == shared::kKeyed) {
    // The record's survival (core/survival.h) decided by its own cell in the table this pass is adding to, not the one
    // before the frame: its variance is whatever the frame's adds that came first made it.
    const SurvivalInPassArgs& v = *args.survival;
    const shared::ProbeScheme scheme = args.scheme();
    double p = 1.0;  // a cell not found, or of fewer than two samples, says nothing of its variance
    for (std::uint32_t probe = 0; probe < args.probe_limit; ++probe) {
      const std::uint32_t s = shared::CandidateSlot(scheme, key.slot0, probe);
      const std::uint64_t tag = co_await ctx.Load(b.tags, s);
      const std::uint64_t count = co_await ctx.Load(b.counts, s);
      const std::uint32_t step = shared::LookupStep(tag, StoredIdentity(key), count);
      if (step == shared::kLookupEnd) break;
      if (step != shared::kLookupFound) continue;
      if (count >= 2) {
        std::array<std::uint64_t, 3> fixed_sum{};
        std::array<float, 3> float_sum{};
        for (int c = 0; c < 3; ++c) {
          fixed_sum[c] = co_await ctx.Load(b.sums, std::uint64_t(s) * 3 + c);
          float_sum[c] = std::bit_cast<float>(std::uint32_t(fixed_sum[c]));
        }
        const std::uint64_t square = co_await ctx.Load(b.squares, s);
        const CellMoments moments =
            MomentsOf(args.accumulation, fixed_sum, float_sum, square, std::bit_cast<float>(std::uint32_t(square)),
                      count, v.fixed_point_bits, v.square_bits);
        p = SurvivalProbability(v.params, moments.variance);
      }
      break;
    }
    contribution = SurvivingContribution(v.params, glm::dvec3(v.traced[i]), v.draws[i], p);
  }
  if (evict_in_pass && args.eviction && i < args.capacity) {
    // Evict slot i as the eviction pass would, but while other threads insert: a slot they touch this frame may
    // still show its old last-seen frame, or hold only part of their adds, when it is zeroed.
    const EvictionArgs& e = *args.eviction;
    if (co_await ctx.Load(b.tags, i) != kEmptyTag && co_await ctx.Load(b.counts, i) != 0 &&
        e.eviction.Evicts(e.frame, std::uint32_t(co_await ctx.Load(b.last_seen, i)))) {
      for (int c = 0; c < 3; ++c) co_await ctx.Store(b.sums, std::uint64_t(i) * 3 + c, 0);
      co_await ctx.Store(b.counts, i, 0);
      co_await ctx.AtomicAdd(e.evicted, 0, 1);
    }
  }
  if (!args.accepted[i] || key.status != shared::kKeyed) {
    co_await ctx.Store(b.placements, i, kNotPlaced);
    co_return;
  }
  // D3: the reduced fingerprint without its 0 -> 1 fix.
  const SlotTag fingerprint = defect == Defect::kD3ZeroFingerprint
                                  ? shared::FullFingerprint(key.words) >> (32u - args.fingerprint_bits)
                                  : StoredIdentity(key);
  const bool fixed = IntegerSums(args.accumulation);
  bool placed = false;
  const shared::ProbeScheme scheme = args.scheme();
  // SHaRC #4: a record whose candidates are all taken is given the "invalid" index masked into a slot, and adds
  // there: one step past its candidates.
  const bool masked_failure = defect == Defect::kFullBucketMasked;
  // SHaRC #5: bucket-window's window not clamped to the table, so a home slot near the end probes past it.
  const bool unclamped_window = defect == Defect::kWindowPastTheEnd && scheme.kind == shared::kProbeBucketWindow;
  for (std::uint32_t probe = 0; probe < args.probe_limit + (masked_failure ? 1u : 0u); ++probe) {
    const bool past_the_candidates = probe == args.probe_limit;
    // D8: the probe index clamped to the last slot, or not wrapped at all, instead of wrapped.
    const std::uint32_t slot = past_the_candidates                   ? 0xFFFFFFFFu & (args.capacity - 1u)
                               : defect == Defect::kD8ClampedProbe   ? std::min(key.slot0 + probe, args.capacity - 1u)
                               : defect == Defect::kD8UnwrappedProbe ? key.slot0 + probe
                               : unclamped_window                    ? key.slot0 + probe
                                                                     : shared::CandidateSlot(scheme, key.slot0, probe);
    std::uint64_t tag = past_the_candidates ? fingerprint : co_await ctx.Load(b.tags, slot);
    bool claimed = false;
    if (tag == kEmptyTag) {
      if (defect == Defect::kD13LoadThenStoreClaim) {  // D13: claim by a plain store after the load
        co_await ctx.Store(b.tags, slot, fingerprint);
      } else if (defect == Defect::kWeakCasOldValue || weak_claim) {
        // A weak compare-and-swap. Bevy #24767 read its verdict from the old value alone, so a spurious failure (the
        // word still 0) counts as a claim while the slot stays empty; the correct loop retries until the swap wrote
        // or the word holds a tag.
        for (;;) {
          const simt::ThreadContext::CasResult swap = co_await ctx.AtomicCasWeak(b.tags, slot, kEmptyTag, fingerprint);
          if (defect == Defect::kWeakCasOldValue || swap.exchanged || swap.old != kEmptyTag) {
            tag = swap.old;
            claimed = defect == Defect::kWeakCasOldValue ? swap.old == kEmptyTag : swap.exchanged;
            break;
          }
        }
      } else {
        tag = co_await ctx.AtomicCas(b.tags, slot, kEmptyTag, fingerprint);
        claimed = tag == kEmptyTag;
      }
    }
    const bool matches = defect == Defect::kFullKeyLowWord
                             ? std::uint32_t(tag) == std::uint32_t(fingerprint)  // the low words alone
                             : tag == fingerprint;
    if (tag != kEmptyTag && !matches) continue;
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t index = std::uint64_t(slot) * 3 + c;
      if (defect == Defect::kD9NonAtomicAdd) {  // D9: read-modify-write without an atomic
        const std::uint64_t old = co_await ctx.Load(b.sums, index);
        const std::uint64_t sum =
            fixed ? old + shared::ToFixedPoint(contribution[c], args.fixed_point_scale)
                  : std::bit_cast<std::uint32_t>(std::bit_cast<float>(std::uint32_t(old)) + contribution[c]);
        co_await ctx.Store(b.sums, index, sum);
      } else if (fixed) {
        // D11: truncated, not rounded half to even.
        const std::uint64_t add = defect == Defect::kD11TruncatedFixedPoint
                                      ? std::uint64_t(contribution[c] * args.fixed_point_scale)
                                      : shared::ToFixedPoint(contribution[c], args.fixed_point_scale);
        const std::uint64_t old = co_await ctx.AtomicAdd(b.sums, index, add);
        if (SumAddWrapped(args.accumulation, old, add)) co_await ctx.AtomicAdd(b.wraps, 0, 1);
      } else {
        co_await ctx.AtomicAddFloat(b.sums, index, std::bit_cast<std::uint32_t>(contribution[c]));
      }
    }
    // --second-moments: the record's square, as the correct kernel adds it.
    if (b.keeps_squares && fixed) {
      const std::uint64_t add = shared::SquareToFixedPoint(contribution, args.square_scale);
      if (SumAddWrapped(args.accumulation, co_await ctx.AtomicAdd(b.squares, slot, add), add))
        co_await ctx.AtomicAdd(b.wraps, 0, 1);
    } else if (b.keeps_squares) {
      co_await ctx.AtomicAddFloat(b.squares, slot, std::bit_cast<std::uint32_t>(shared::SquareAsFloat(contribution)));
    }
    if (defect == Defect::kD9NonAtomicAdd) {
      const std::uint64_t count = co_await ctx.Load(b.counts, slot);
      co_await ctx.Store(b.counts, slot, count + 1);
    } else if (defect == Defect::kCountStoreClaimFirst || defect == Defect::kCountStoreJoinFirst) {
      // The claimer "initialises" the count it just claimed with a plain store while records that found the tag
      // add atomically: an add that lands before the store is lost. Both branch orders, as a shader has them.
      if (defect == Defect::kCountStoreClaimFirst) {
        if (claimed) {
          co_await ctx.Store(b.counts, slot, 1);
        } else {
          co_await ctx.AtomicAdd(b.counts, slot, 1);
        }
      } else {
        if (!claimed) {
          co_await ctx.AtomicAdd(b.counts, slot, 1);
        } else {
          co_await ctx.Store(b.counts, slot, 1);
        }
      }
    } else if (count32) {  // D12: a 32-bit counter, one compare-and-swap at a time, that wraps silently
      std::uint64_t count = co_await ctx.Load(b.counts, slot);
      for (;;) {
        const std::uint64_t seen = co_await ctx.AtomicCas(b.counts, slot, count, (count + 1) & 0xFFFFFFFFu);
        if (seen == count) break;
        count = seen;
      }
    } else if (CountAddWrapped(args.accumulation, co_await ctx.AtomicAdd(b.counts, slot, 1))) {
      co_await ctx.AtomicAdd(b.wraps, 1, 1);
    }
    // Last-seen by every writer; the defect stores it from the record that claimed the slot only.
    if (args.track_last_seen && (defect != Defect::kLastSeenClaimerOnly || claimed)) {
      co_await ctx.Store(b.last_seen, slot, args.frame);
    }
    if (blend_in_pass && args.temporal) {
      // D10: the slot blended right after this record's add, from the table still being accumulated: other
      // records' adds may come before or after it, and a slot blends once per record instead of once.
      const TemporalArgs& t = *args.temporal;
      CellState before, accumulated;
      const std::uint64_t old_word = co_await ctx.Load(t.previous_counts, slot);
      const std::uint64_t new_word = co_await ctx.Load(b.counts, slot);
      // packed-decimal's count word holds the frame counter too (core/shared/packed_sums.h).
      before.count = packed ? shared::PackedCount(std::uint32_t(old_word)) : old_word;
      accumulated.count = packed ? shared::PackedCount(std::uint32_t(new_word)) : new_word;
      if (before.count != 0 && new_word != old_word) {
        for (int c = 0; c < 3; ++c) {
          const std::uint64_t word = std::uint64_t(slot) * 3 + c;
          before.fixed_sum[c] = co_await ctx.Load(t.previous_sums, word);
          accumulated.fixed_sum[c] = co_await ctx.Load(b.sums, word);
          before.float_sum[c] = std::bit_cast<float>(std::uint32_t(before.fixed_sum[c]));
          accumulated.float_sum[c] = std::bit_cast<float>(std::uint32_t(accumulated.fixed_sum[c]));
        }
        const CellState blended = BlendCellState(t.params, args.accumulation, before, accumulated);
        for (int c = 0; c < 3; ++c) {
          co_await ctx.Store(b.sums, std::uint64_t(slot) * 3 + c,
                             fixed ? blended.fixed_sum[c] : std::bit_cast<std::uint32_t>(blended.float_sum[c]));
        }
        co_await ctx.Store(
            b.counts, slot,
            packed ? shared::PackCountWord(std::uint32_t(blended.count), shared::PackedFrames(std::uint32_t(new_word)))
                   : blended.count);
      }
    }
    co_await ctx.Store(b.placements, i, slot);
    placed = true;
    if (defect != Defect::kD2AddsAgain) co_return;  // D2: keeps probing and adds again (Meijer Algorithm 4)
  }
  if (!placed) co_await ctx.Store(b.placements, i, kProbeFailure);
}

// The coarser levels keyed at the unjittered position: the record's own cell is jittered, its parents are not.
KeyResult UnjitteredKeyOfLevel(const AccumulateArgs& args, std::uint32_t record, std::uint32_t level) {
  if (level == 0) return args.keys[record];
  KeyParams unjittered = args.key_params;
  unjittered.jitter_scale = 0.0f;
  return shared::KeyAtLevel(args.key_params, shared::ComputeKey(unjittered, args.records[record]), level);
}

simt::KernelTask LevelUnjittered(simt::ThreadContext& c, const AccumulateArgs& a) {
  return AccumulateLevels(c, a, UnjitteredKeyOfLevel);
}

// Meijer's Algorithm 4 as written (Meijer's thesis, "HPSF pseudocode: Collect contributions"), for linear probing:
// a first loop over the window adds to every slot that holds the record's identity, without stopping, up to the
// first empty slot, which it remembers (slot0 where it found none); a second loop from there, probe_limit slots long
// and so past the window, claims by compare-and-swap and adds where the swap found the slot empty or holding the
// identity, then stops. A record of a cell already in the table adds to the cell and again to the next free slot,
// which it claims for the same cell. Its placement is the slot the algorithm returns (the second loop's add), else
// its last add, else a probe failure. Each add is the record's sums and one count, as the correct kernel's.
simt::KernelTask Algorithm4AsWritten(simt::ThreadContext& ctx, const AccumulateArgs& args) {
  const std::uint32_t i = ctx.Thread();
  const KeyResult& key = args.keys[i];
  const TableBuffers& b = args.buffers;
  if (!args.accepted[i] || key.status != shared::kKeyed) {
    co_await ctx.Store(b.placements, i, kNotPlaced);
    co_return;
  }
  const SlotTag identity = StoredIdentity(key);
  const Record& r = args.records[i];
  const std::uint32_t mask = args.capacity - 1u;
  std::uint32_t placement = kProbeFailure;
  bool second = false;  // which of the two loops
  std::uint32_t index = 0, end = args.probe_limit;
  for (;;) {
    if (index == end) {
      if (second) break;
      second = true;  // the window held no empty slot: the second loop starts at slot0
      index = 0;
      end = args.probe_limit;
      continue;
    }
    const std::uint32_t slot = (key.slot0 + index) & mask;
    if (!second) {
      if (co_await ctx.Load(b.tags, slot) != identity) {
        if (co_await ctx.Load(b.tags, slot) == kEmptyTag) {  // the algorithm loads the tag again
          second = true;
          end = index + args.probe_limit;  // from the first free slot on
          continue;
        }
        ++index;
        continue;
      }
    } else {
      const std::uint64_t original = co_await ctx.AtomicCas(b.tags, slot, kEmptyTag, identity);
      if (original != kEmptyTag && original != identity) {
        ++index;
        continue;
      }
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
    if (CountAddWrapped(args.accumulation, co_await ctx.AtomicAdd(b.counts, slot, 1)))
      co_await ctx.AtomicAdd(b.wraps, 1, 1);
    if (args.track_last_seen) co_await ctx.Store(b.last_seen, slot, args.frame);
    placement = slot;
    if (second) break;
    ++index;
  }
  co_await ctx.Store(b.placements, i, placement);
}

simt::KernelTask D2(simt::ThreadContext& c, const AccumulateArgs& a) { return Mutant(c, a, Defect::kD2AddsAgain); }
simt::KernelTask D3(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kD3ZeroFingerprint);
}
simt::KernelTask D8(simt::ThreadContext& c, const AccumulateArgs& a) { return Mutant(c, a, Defect::kD8ClampedProbe); }
simt::KernelTask D8Unwrapped(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kD8UnwrappedProbe);
}
simt::KernelTask D9(simt::ThreadContext& c, const AccumulateArgs& a) { return Mutant(c, a, Defect::kD9NonAtomicAdd); }
simt::KernelTask D13(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kD13LoadThenStoreClaim);
}
simt::KernelTask D11(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kD11TruncatedFixedPoint);
}
simt::KernelTask CountStoreClaimFirst(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kCountStoreClaimFirst);
}
simt::KernelTask CountStoreJoinFirst(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kCountStoreJoinFirst);
}
simt::KernelTask LastSeenClaimerOnly(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kLastSeenClaimerOnly);
}
simt::KernelTask FullBucketMasked(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kFullBucketMasked);
}
simt::KernelTask WindowPastTheEnd(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kWindowPastTheEnd);
}
simt::KernelTask WeakCasOldValue(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kWeakCasOldValue);
}
simt::KernelTask FullKeyLowWord(simt::ThreadContext& c, const AccumulateArgs& a) {
  return Mutant(c, a, Defect::kFullKeyLowWord);
}

}  // namespace

simt::KernelTask D10BlendDuringAccumulate(simt::ThreadContext& ctx, const AccumulateArgs& args) {
  return Mutant(ctx, args, Defect::kNone, {.blend_in_pass = true});
}

simt::KernelTask EvictDuringAccumulate(simt::ThreadContext& ctx, const AccumulateArgs& args) {
  return Mutant(ctx, args, Defect::kNone, {.evict_in_pass = true});
}

simt::KernelTask TransportDuringAccumulate(simt::ThreadContext& ctx, const AccumulateArgs& args) {
  return Mutant(ctx, args, Defect::kNone, {.transport_in_pass = true});
}

simt::KernelTask SurvivalDuringAccumulate(simt::ThreadContext& ctx, const AccumulateArgs& args) {
  return Mutant(ctx, args, Defect::kNone, {.survival_in_pass = true});
}

simt::KernelTask D12Count32Bit(simt::ThreadContext& ctx, const AccumulateArgs& args) {
  return Mutant(ctx, args, Defect::kNone, {.count32 = true});
}

simt::KernelTask AccumulateWithWeakCas(simt::ThreadContext& ctx, const AccumulateArgs& args) {
  return Mutant(ctx, args, Defect::kNone, {.weak_claim = true});
}

simt::KernelTask D7ReclaimEveryTombstone(simt::ThreadContext& ctx, const EvictionArgs& args) {
  const auto slot =
      args.list.on ? static_cast<std::uint32_t>(co_await ctx.Load(args.list.slots, ctx.Thread())) : ctx.Thread();
  if (co_await ctx.Load(args.buffers.tags, slot) == kEmptyTag) co_return;
  if (co_await ctx.Load(args.buffers.counts, slot) != 0) co_return;
  co_await ctx.Store(args.buffers.tags, slot, kEmptyTag);  // the one change: no look at the live slots after it
}

simt::KernelTask FinishPruneCountOneWhenEmpty(simt::ThreadContext& ctx, const CompactionArgs& args) {
  const std::uint64_t kept = co_await ctx.Load(args.list.next_count, 0);
  co_await ctx.Store(args.list.count, 0, kept == 0 ? 1 : kept);  // the one change: an empty list counts one
  co_await ctx.Store(args.list.next_count, 0, 0);
}

simt::KernelTask SelectVictimsWrongSign(simt::ThreadContext& ctx, const EvictionArgs& args) {
  const std::uint32_t i = ctx.Thread();
  const TableBuffers& b = args.buffers;
  if (co_await ctx.Load(b.placements, i) != kProbeFailure) co_return;
  bool found = false;
  std::uint32_t victim = 0;
  SlotTag victim_tag = 0;
  std::uint64_t victim_priority = 0;
  const shared::ProbeScheme scheme = args.scheme();
  for (std::uint32_t probe = 0; probe < args.probe_limit; ++probe) {
    const std::uint32_t slot = shared::CandidateSlot(scheme, args.keys[i].slot0, probe);
    const SlotTag tag = co_await ctx.Load(b.tags, slot);
    if (tag == kEmptyTag || tag == shared::kTombstoneTag) continue;
    const std::uint64_t count = co_await ctx.Load(b.counts, slot);
    const auto last_seen = static_cast<std::uint32_t>(co_await ctx.Load(b.last_seen, slot));
    if (count == 0 || last_seen == args.frame) continue;
    const std::uint64_t priority = shared::EvictionPriority(last_seen, count);
    // The one change: the compare's operands swapped, so the highest priority is evicted.
    if (!found || shared::EvictedBefore(victim_priority, victim_tag, priority, tag)) {
      found = true;
      victim = slot;
      victim_priority = priority;
      victim_tag = tag;
    }
  }
  if (found) co_await ctx.Store(args.victims, victim, 1);
}

Defect ParseDefect(const std::string& text) {
  if (text == "none") return Defect::kNone;
  if (text == "D2") return Defect::kD2AddsAgain;
  if (text == "algorithm-4") return Defect::kAlgorithm4AsWritten;
  if (text == "D3") return Defect::kD3ZeroFingerprint;
  if (text == "D8") return Defect::kD8ClampedProbe;
  if (text == "D8-unwrapped") return Defect::kD8UnwrappedProbe;
  if (text == "D9") return Defect::kD9NonAtomicAdd;
  if (text == "D11") return Defect::kD11TruncatedFixedPoint;
  if (text == "D13") return Defect::kD13LoadThenStoreClaim;
  if (text == "count-store-claim-first") return Defect::kCountStoreClaimFirst;
  if (text == "count-store-join-first") return Defect::kCountStoreJoinFirst;
  if (text == "last-seen-claimer-only") return Defect::kLastSeenClaimerOnly;
  if (text == "full-bucket-masked") return Defect::kFullBucketMasked;
  if (text == "window-past-the-end") return Defect::kWindowPastTheEnd;
  if (text == "weak-cas-old-value") return Defect::kWeakCasOldValue;
  if (text == "full-key-low-word") return Defect::kFullKeyLowWord;
  if (text == "level-unjittered") return Defect::kLevelUnjittered;
  if (text == "level-wrong-count") return Defect::kLevelWrongCount;
  if (text == "search-claims") return Defect::kSearchClaims;
  if (text == "search-stops-at-tombstone") return Defect::kSearchStopsAtTombstone;
  if (text == "stencil-truncated") return Defect::kStencilTruncated;
  throw ConfigError("--inject-defect",
                    "expected none, D2, D3, D8, D8-unwrapped, D9, D11, D13, count-store-claim-first, "
                    "count-store-join-first, last-seen-claimer-only, full-bucket-masked, window-past-the-end, "
                    "weak-cas-old-value, full-key-low-word, level-unjittered, level-wrong-count, search-claims, "
                    "search-stops-at-tombstone, stencil-truncated or algorithm-4; got '" +
                        text + "'");
}

std::string ToString(Defect defect) {
  switch (defect) {
    case Defect::kNone:
      return "none";
    case Defect::kD2AddsAgain:
      return "D2";
    case Defect::kAlgorithm4AsWritten:
      return "algorithm-4";
    case Defect::kD3ZeroFingerprint:
      return "D3";
    case Defect::kD8ClampedProbe:
      return "D8";
    case Defect::kD8UnwrappedProbe:
      return "D8-unwrapped";
    case Defect::kD9NonAtomicAdd:
      return "D9";
    case Defect::kD13LoadThenStoreClaim:
      return "D13";
    case Defect::kD11TruncatedFixedPoint:
      return "D11";
    case Defect::kCountStoreClaimFirst:
      return "count-store-claim-first";
    case Defect::kCountStoreJoinFirst:
      return "count-store-join-first";
    case Defect::kLastSeenClaimerOnly:
      return "last-seen-claimer-only";
    case Defect::kFullBucketMasked:
      return "full-bucket-masked";
    case Defect::kWindowPastTheEnd:
      return "window-past-the-end";
    case Defect::kWeakCasOldValue:
      return "weak-cas-old-value";
    case Defect::kFullKeyLowWord:
      return "full-key-low-word";
    case Defect::kLevelUnjittered:
      return "level-unjittered";
    case Defect::kLevelWrongCount:
      return "level-wrong-count";
    case Defect::kSearchClaims:
      return "search-claims";
    case Defect::kSearchStopsAtTombstone:
      return "search-stops-at-tombstone";
    case Defect::kStencilTruncated:
      return "stencil-truncated";
  }
  return "?";
}

AccumulateKernelFn KernelWithDefect(Defect defect) {
  switch (defect) {
    case Defect::kNone:
      return AccumulateKernel;
    case Defect::kD2AddsAgain:
      return D2;
    case Defect::kAlgorithm4AsWritten:
      return Algorithm4AsWritten;
    case Defect::kD3ZeroFingerprint:
      return D3;
    case Defect::kD8ClampedProbe:
      return D8;
    case Defect::kD8UnwrappedProbe:
      return D8Unwrapped;
    case Defect::kD9NonAtomicAdd:
      return D9;
    case Defect::kD13LoadThenStoreClaim:
      return D13;
    case Defect::kD11TruncatedFixedPoint:
      return D11;
    case Defect::kCountStoreClaimFirst:
      return CountStoreClaimFirst;
    case Defect::kCountStoreJoinFirst:
      return CountStoreJoinFirst;
    case Defect::kLastSeenClaimerOnly:
      return LastSeenClaimerOnly;
    case Defect::kFullBucketMasked:
      return FullBucketMasked;
    case Defect::kWindowPastTheEnd:
      return WindowPastTheEnd;
    case Defect::kWeakCasOldValue:
      return WeakCasOldValue;
    case Defect::kFullKeyLowWord:
      return FullKeyLowWord;
    case Defect::kLevelUnjittered:
      return LevelUnjittered;
    case Defect::kLevelWrongCount:
    case Defect::kSearchClaims:
    case Defect::kSearchStopsAtTombstone:
    case Defect::kStencilTruncated:
      return AccumulateKernel;
  }
  return AccumulateKernel;
}

EmulatorOptions WithDefect(EmulatorOptions options, Defect defect) {
  options.resolve_defect = defect == Defect::kLevelWrongCount          ? ResolveDefect::kLevelWrongCount
                           : defect == Defect::kSearchClaims           ? ResolveDefect::kClaims
                           : defect == Defect::kSearchStopsAtTombstone ? ResolveDefect::kStopsAtTombstone
                           : defect == Defect::kStencilTruncated       ? ResolveDefect::kStencilTruncated
                                                                       : ResolveDefect::kNone;
  return options;
}

}  // namespace hpsf
