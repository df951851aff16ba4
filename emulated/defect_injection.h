// Known defects (docs/design/defects.md) injected into the accumulate kernel, one at a time, so the harness can prove
// its gate has teeth: `hpsf crosscheck --inject-defect D9` must fail. Each variant is the correct kernel
// (accumulate_kernel.cpp) with exactly one change.
#ifndef HPSF_EMULATED_DEFECT_INJECTION_H
#define HPSF_EMULATED_DEFECT_INJECTION_H

#include <string>

#include "emulated/emulated_filter.h"

namespace hpsf {

enum class Defect {
  kNone,
  kD2AddsAgain,            // adds on a match and keeps probing, adding again (Meijer Algorithm 4)
  kD3ZeroFingerprint,      // the reduced fingerprint without its 0 -> 1 fix: equal to the empty tag
  kD8ClampedProbe,         // the probe index clamped to the last slot instead of wrapped
  kD8UnwrappedProbe,       // the probe index not wrapped at all: writes past the end of the table
  kD9NonAtomicAdd,         // read-modify-write of sums and counts without atomics
  kD13LoadThenStoreClaim,  // a slot claimed by load-then-store instead of compare-and-swap
  // The three classes a new user's planted bugs showed `hpsf fuzz` must find unaided:
  kD11TruncatedFixedPoint,  // fixed64 by truncation instead of rounding: hidden where c * 2^F is an integer
  kCountStoreClaimFirst,    // the claimer sets the count with a plain store of 1, others add atomically (claim
  kCountStoreJoinFirst,     // branch written first, or the joiners' branch first): a race on the count
  kLastSeenClaimerOnly,     // the last-seen frame stored by the claiming record only: a slot joined later looks stale
  // Bugs production caches shipped (docs/design/defects.md, "Shipped bugs"):
  kFullBucketMasked,  // SHaRC #4: a full bucket's "invalid" index masked into slot capacity - 1, and added there
  kWindowPastTheEnd,  // SHaRC #5: bucket-window's window not clamped to the table: probes run past its end
  kWeakCasOldValue,   // Bevy #24767: a weak CAS's claim read from the old value alone: a spurious failure "claims"
  // A full key's bug (--key-identity full): a 64-bit tag matched by its low word alone, as a 32-bit compare of a
  // 64-bit key does, so cells that share the low word (the same x, and y modulo 2^15) share a slot.
  kFullKeyLowWord,
  // Multi-level accumulation (--levels, core/shared/levels.h): the coarser cells keyed at the record's unjittered
  // position, so they no longer nest its own (jittered) cell.
  kLevelUnjittered,
  // The resolve's threshold judged by the count of the record's own cell at every level
  // (resolve_LEVEL_WRONG_COUNT.spv).
  kLevelWrongCount,
  // The resolve's neighbourhood search (--neighbour-search, emulated/broken_resolve.h): a lookup that claims, one that
  // stops at a tombstone, a stencil whose side comes from truncation.
  kSearchClaims,
  kSearchStopsAtTombstone,
  kStencilTruncated,
  // Meijer's Algorithm 4 as written (docs/design/defects.md, "Meijer's Algorithm 4"): adds to every slot of the window
  // holding the record's identity up to the first empty one, then claims from there and adds again.
  kAlgorithm4AsWritten,
};

// "none", "D2", "D3", "D8", "D8-unwrapped", "D9", "D11", "D13", "count-store-claim-first",
// "count-store-join-first", "last-seen-claimer-only", "full-bucket-masked", "window-past-the-end",
// "weak-cas-old-value", "full-key-low-word", "level-unjittered", "level-wrong-count", "search-claims",
// "search-stops-at-tombstone", "stencil-truncated", "algorithm-4"; a ConfigError naming --inject-defect otherwise.
Defect ParseDefect(const std::string& text);
std::string ToString(Defect defect);
// The accumulate kernel a defect runs (hpsf's own where the defect lies in another pass).
AccumulateKernelFn KernelWithDefect(Defect defect);
// The options with the defect's broken resolve search, where it has one.
EmulatorOptions WithDefect(EmulatorOptions options, Defect defect);

// D7 (docs/design/defects.md), in the eviction pass (emulated/eviction_kernels.h): the reclaim empties every tombstone,
// so an eviction leaves a hole that a live cell's key probed past; its next lookup claims the hole and splits the cell.
// Not a Defect value yet: it takes a sequence of frames, which the single-frame commands do not run.
simt::KernelTask D7ReclaimEveryTombstone(simt::ThreadContext& ctx, const EvictionArgs& args);

// Bevy #21904 (docs/design/defects.md, "Shipped bugs"), in compaction (emulated/compaction_kernels.h): the prune's
// count is 1 when it kept no slot, so the list names a slot that holds nothing.
simt::KernelTask FinishPruneCountOneWhenEmpty(simt::ThreadContext& ctx, const CompactionArgs& args);

// Priority eviction's compare of the wrong sign: the selection evicts, in a failed record's window, the
// untouched live slot of highest priority instead of lowest (the most recently seen, most sampled cell).
simt::KernelTask SelectVictimsWrongSign(simt::ThreadContext& ctx, const EvictionArgs& args);

// D10: the accumulate that blends its slot (core/temporal.h) right after each record's add, reading averages from
// the table it is still accumulating instead of leaving the blend to a pass after it: torn (sum, count), and a
// slot blended once per record. Not a Defect value: only a frame after the first blends.
simt::KernelTask D10BlendDuringAccumulate(simt::ThreadContext& ctx, const AccumulateArgs& args);

// Several filtered bounces' transport inside the accumulate (TransportDefect::kReadsCurrentTable, D10's cousin): each
// record looks up its scattered vertex's cell in the table this launch is adding to (args.transport), reading
// whichever adds of the frame came first, then adds its transported contribution. One level.
simt::KernelTask TransportDuringAccumulate(simt::ThreadContext& ctx, const AccumulateArgs& args);

// Path survival decided inside the accumulate (emulated/broken_survival.h, D10's cousin): each record looks its own
// cell up in the table this launch is adding to (args.survival), reads its variance from whichever adds of the frame
// came first, and adds its traced light as survival decides by it. One level.
simt::KernelTask SurvivalDuringAccumulate(simt::ThreadContext& ctx, const AccumulateArgs& args);

// An eviction racing an insertion: the accumulate whose thread i first evicts slot i by the policy, as
// the eviction pass would, then inserts its record, saving the pass's launch. Another thread may be inserting
// into slot i meanwhile: its last-seen store may come after the eviction's read, or its adds before the zeroing,
// so a cell the frame touches is evicted, whole or in part. Not a Defect value: only a frame after the first
// evicts.
simt::KernelTask EvictDuringAccumulate(simt::ThreadContext& ctx, const AccumulateArgs& args);

// D12: the accumulate with a 32-bit sample counter that wraps silently at 2^32 adds to one cell. Not a Defect value
// either: only a long sequence of frames (or a table loaded with a large count) reaches it.
simt::KernelTask D12Count32Bit(simt::ThreadContext& ctx, const AccumulateArgs& args);

// Not a defect: the accumulate whose claim is a weak compare-and-swap in a retry loop, as a CPU or WGSL cache writes
// it. Correct under any --spurious-cas; weak-cas-old-value is it with the loop's verdict read from the old value.
simt::KernelTask AccumulateWithWeakCas(simt::ThreadContext& ctx, const AccumulateArgs& args);

}  // namespace hpsf

#endif  // HPSF_EMULATED_DEFECT_INJECTION_H
