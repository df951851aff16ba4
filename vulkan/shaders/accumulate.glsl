// The accumulate pass of docs/design/algorithm.md, record by record: the key from core/shared, then
// bounded probing of slot0's candidates (core/shared/probe_scheme.h); a slot whose tag is the fingerprint is joined, an empty one claimed with
// atomicCompSwap; each channel is added atomically, then the count, and the record's slot is stored. fixed64
// reports wrap from the add's return value. With eviction, the slot's last-seen frame is stored after the adds;
// a tombstone (an evicted slot that keeps its tag) is joined or passed like any slot, never claimed; with priority
// eviction (table.claim_tombstones) its tombstones may be claimed (FindOrClaim). accumulate_fixed64.comp,
// accumulate_float32.comp and accumulate_packed_decimal.comp define the sums type and include this.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/key.h"
#include "../../core/shared/levels.h"
#include "../../core/shared/fixed_point.h"
#include "../../core/shared/packed_sums.h"
#include "../../core/shared/table_params.h"
#include "../../core/shared/eviction_priority.h"
#if defined(HPSF_FIXED64) || defined(HPSF_DEFECT_D10)  // fixed64's squares are formed in double
#include "float_controls_fp64.glsl"
#endif
#include "../../core/shared/second_moment.h"
#if defined(HPSF_DEFECT_D10)
#define HPSF_TABLE_INTERFACE_TEMPORAL
#include "../../core/shared/temporal_blend.h"
#endif
#include "subgroup_runs.glsl"
#include "table_interface.glsl"
#include "slot_tags.glsl"

// The host dispatches ceil(n / (128 * 16)) workgroups, at most 65535 (vulkan/vulkan_filter.cpp).
const uint kRecordsPerInvocation = 16u;
layout(local_size_x = 128) in;

// The test suite compiles this file once more per known defect of docs/design/defects.md (HPSF_DEFECT_D2, _D3, _D8, _D9,
// _D12, _D13, each exactly one change), per bug a production cache shipped (_FULL_BUCKET_MASKED, SHaRC #4;
// _WINDOW_PAST_THE_END, SHaRC #5), of a full key (_FULL_KEY_LOW_WORD, matched by its low word), Meijer's Algorithm 4 as
// written (_ALGORITHM_4) and of frames (HPSF_DEFECT_D10, _EVICT_RACE), and runs the variants through
// --accumulate-spv: the gate must catch each. HPSF_DEFECT_D11, _COUNT_STORE_CLAIM_FIRST, _COUNT_STORE_JOIN_FIRST
// and _LAST_SEEN_CLAIMER_ONLY are the classes `hpsf fuzz` must find unaided (a rounding defect the automatic F
// hides, a race one execution order hides, a frame-state defect one frame hides). HPSF_DEFECT_SLOT0_FOR_FAILURE and HPSF_DEFECT_GARBAGE_* write words
// the host must not trust (core/read_back_check.h): each must be named as a failure, never crash the host.

#if defined(HPSF_DEFECT_D12)
layout(std430, binding = 4) buffer CountWords { uint count_words[]; };  // binding 4 again, as 32-bit words
#endif
#if defined(HPSF_DEFECT_ALGORITHM_4)
const bool ALGORITHM_4 = true;  // the insertion below replaces the correct loop
#else
const bool ALGORITHM_4 = false;
#endif
#if defined(HPSF_DEFECT_EVICT_RACE)
layout(std430, binding = 8) buffer LastSeenRead { uint last_seen_read[]; };  // binding 8 again, read too

// An eviction racing the insertions: slot i evicted by strict's rule (not touched since an earlier frame) by the
// invocation of record i, in this pass instead of the eviction pass after it, while other invocations may be
// inserting into it.
void EvictDuringAccumulate(uint slot, TableParams t) {
  if (t.track_last_seen == 0u || slot >= t.capacity) return;
  if (tags[slot] == 0u || counts[slot] == uint64_t(0) || last_seen_read[slot] >= t.frame) return;
  for (uint c = 0u; c < 3u; ++c) sums[slot * 3u + c] = HPSF_SUMS_TYPE(0);
  counts[slot] = uint64_t(0);
}
#endif

#if defined(HPSF_DEFECT_GARBAGE_KEYS) || defined(HPSF_DEFECT_GARBAGE_TAGS) || defined(HPSF_DEFECT_GARBAGE_SUMS) || \
    defined(HPSF_DEFECT_GARBAGE_COUNTS) || defined(HPSF_DEFECT_GARBAGE_PLACEMENTS) ||                         \
    defined(HPSF_DEFECT_GARBAGE_STATS) || defined(HPSF_DEFECT_GARBAGE_LAST_SEEN)
#define HPSF_GARBAGE_OUTPUT
// A shader that leaves garbage in one output binding, after its record's correct work: the host must name the
// failure (exit 2), never crash on it. The words are a multiplicative hash of the record, mostly far out of range.
uint Garbage(uint i) { return i * 2654435761u + 0x9E3779B9u; }

void WriteGarbage(uint i, TableParams t) {
  uint slot = i & (t.capacity - 1u);
#if defined(HPSF_DEFECT_GARBAGE_KEYS)
  for (uint v = 0u; v < 3u; ++v) key_vectors[i * 3u + v] = uvec4(Garbage(i + v), Garbage(i ^ v), Garbage(~i), Garbage(i) >> v);
#elif defined(HPSF_DEFECT_GARBAGE_TAGS)
  tags[slot] = Garbage(i);
#elif defined(HPSF_DEFECT_GARBAGE_SUMS)
  sums[slot * 3u] = HPSF_SUMS_TYPE(Garbage(i));
#elif defined(HPSF_DEFECT_GARBAGE_COUNTS)
  counts[slot] = uint64_t(Garbage(i)) << 20;
#elif defined(HPSF_DEFECT_GARBAGE_PLACEMENTS)
  placements[i] = Garbage(i);
#elif defined(HPSF_DEFECT_GARBAGE_STATS)
  if (i == 0u) {
    wraps = uint64_t(Garbage(i)) << 24;
    count_wraps = uint64_t(Garbage(i + 1u)) << 24;
  }
#elif defined(HPSF_DEFECT_GARBAGE_LAST_SEEN)
  last_seen[slot] = Garbage(i);
#endif
}
#endif

// claimed: this record's compare-and-swap claimed the slot (only the COUNT_STORE variants look at it).
void AddToSlot(uint slot, Record r, float fixed_point_scale, bool claimed) {
  for (uint c = 0u; c < 3u; ++c) {
#if defined(HPSF_PACKED_DECIMAL)  // 32-bit words at 1000 (packed_sums.h); the host checked each add fits 32 bits
    uint add = uint(ToFixedPoint(r.contribution[c], fixed_point_scale));
    uint old = atomicAdd(sums[slot * 3u + c], add);
    if (old + add < old) atomicAdd(wraps, uint64_t(1));
#elif defined(HPSF_DEFECT_D9)  // read-modify-write without an atomic: lost updates
    sums[slot * 3u + c] += ToFixedPoint(r.contribution[c], fixed_point_scale);
#elif defined(HPSF_DEFECT_D11)  // truncated instead of rounded half to even: a bias hidden where c * 2^F is whole
    precise float scaled = r.contribution[c] * fixed_point_scale;
    atomicAdd(sums[slot * 3u + c], uint64_t(scaled));
#elif defined(HPSF_FIXED64)
    uint64_t add = ToFixedPoint(r.contribution[c], fixed_point_scale);
    uint64_t old = atomicAdd(sums[slot * 3u + c], add);
    if (old + add < old) atomicAdd(wraps, uint64_t(1));
#else
    atomicAdd(sums[slot * 3u + c], r.contribution[c]);
#endif
  }
  // --second-moments (core/shared/second_moment.h): the record's squared brightness, before its count.
#if defined(HPSF_FIXED64)
  if (keeps_squares != 0u) {
    uint64_t add = SquareToFixedPoint(r.contribution.xyz, double(PowerOfTwo(square_bits)));
    uint64_t old = atomicAdd(squares[slot], add);
    if (old + add < old) atomicAdd(wraps, uint64_t(1));
  }
#elif !defined(HPSF_PACKED_DECIMAL)
  if (keeps_squares != 0u) atomicAdd(squares[slot], SquareAsFloat(r.contribution.xyz));
#endif
#if defined(HPSF_PACKED_DECIMAL)  // the count word: a 24-bit count carries into the frame counter at 2^24
  if ((atomicAdd(counts[slot], 1u) & kPackedCountMask) == kPackedCountMask) atomicAdd(count_wraps, uint64_t(1));
#elif defined(HPSF_DEFECT_D9)
  counts[slot] += uint64_t(1);
#elif defined(HPSF_DEFECT_D12)  // a 32-bit sample counter: the low word of the count, which wraps silently
  atomicAdd(count_words[slot * 2u], 1u);
#elif defined(HPSF_DEFECT_COUNT_STORE_CLAIM_FIRST)  // the claimer "initialises" the count with a plain store while
  if (claimed) {                                    // others add atomically: an add before the store is lost
    counts[slot] = uint64_t(1);
  } else {
    atomicAdd(counts[slot], uint64_t(1));
  }
#elif defined(HPSF_DEFECT_COUNT_STORE_JOIN_FIRST)  // the same race with the branches written the other way round
  if (!claimed) {
    atomicAdd(counts[slot], uint64_t(1));
  } else {
    counts[slot] = uint64_t(1);
  }
#else
  // A count of 2^64 - 1 wraps to 0 (docs/design/defects.md, D12): no frame sequence gets there, but a table loaded with one can.
  if (atomicAdd(counts[slot], uint64_t(1)) == ~uint64_t(0)) atomicAdd(count_wraps, uint64_t(1));
#endif
}

#if defined(HPSF_DEFECT_D10)
// D10: the slot blended right after this record's add, from the table still being accumulated (fixed64 sums):
// other records' adds land before or after it, and the slot blends once per record instead of once.
void BlendDuringAccumulate(uint slot, TableParams t) {
  if (t.blending == 0u) return;
  uint64_t old_count = previous_counts[slot];
  uint64_t count = counts[slot];
  if (old_count == uint64_t(0) || count == old_count) return;
  dvec3 old_sum, frame_sum;
  for (int c = 0; c < 3; ++c) {
    uint64_t before = previous_sums[slot * 3u + uint(c)];
    old_sum[c] = double(before);
    frame_sum[c] = double(sums[slot * 3u + uint(c)] - before);
  }
  TemporalBlend b = BlendCell(temporal, old_sum, old_count, frame_sum, count - old_count, 0.0, 0.0);
  if (b.integrated) return;
  for (int c = 0; c < 3; ++c) sums[slot * 3u + uint(c)] = uint64_t(RoundHalfEvenNonNegative(b.sum[c]));
  counts[slot] = b.count;
}
#endif

// Priority eviction's insertion (the emulator's emulated/accumulate_kernel.cpp says why it is right): the cell is
// looked for first, up to the first empty slot, since a claimable tombstone may lie before it; then the first empty
// or tombstone slot is claimed by compare-and-swap, and one that a record of the same cell claimed meanwhile is
// joined. Returns the slot, or kPlacementProbeFailure.
uint FindOrClaim(uint slot0, uint64_t identity, TableParams t, bool full) {
  for (uint probe = 0u; probe < t.probe_limit; ++probe) {
    uint slot = CandidateSlot(ProbeSchemeOf(t), slot0, probe);
    uint64_t tag = LoadTag(slot, full);
    if (tag == identity) return slot;
    if (tag == 0ul) break;
  }
  for (uint probe = 0u; probe < t.probe_limit; ++probe) {
    uint slot = CandidateSlot(ProbeSchemeOf(t), slot0, probe);
    uint64_t tag = LoadTag(slot, full);
    if (tag == 0ul || tag == uint64_t(kTombstoneTag)) {
      uint64_t seen = SwapTag(slot, tag, identity, full);
      tag = seen == tag ? identity : seen;
    }
    if (tag == identity) return slot;
  }
  return kPlacementProbeFailure;
}

#if defined(HPSF_TEAM_KEY) || defined(HPSF_TEAM_KEY_ZERO)
// A team's own key (run with --key-source shader): cells twice as large as hpsf's (its cell words halved), hashed by
// other functions into another home slot and identity. _ZERO lets the identity of every eighth cell be 0, the empty
// marker (Bevy #21953).
KeyResult TeamKey(KeyResult k, KeyParams p) {
  if (k.status != kKeyed) return k;
  k.words.cell_x = uint(int(k.words.cell_x) >> 1);
  k.words.cell_y = uint(int(k.words.cell_y) >> 1);
  k.words.cell_z = uint(int(k.words.cell_z) >> 1);
  uint h = Pcg(k.words.cell_x ^ Pcg(k.words.cell_y ^ Pcg(k.words.cell_z ^ Pcg(k.words.level ^ Pcg(k.words.normal)))));
  k.slot0 = h & p.capacity_mask;
  uint identity = Pcg(h ^ 0x5BD1E995u) >> (32u - p.fingerprint_bits);
#if defined(HPSF_TEAM_KEY_ZERO)
  if ((k.words.cell_x & 7u) == 0u) identity = 0u;
#else
  identity = max(identity, 1u);
#endif
  k.fingerprint = identity;
  k.identity_high = 0u;  // a 32-bit identity, under either --key-identity
  return k;
}
#endif

// Probes for record r's cell of key k, adds r there and returns its slot (or a placement marker).
uint PlaceRecord(KeyResult k, Record r, KeyParams p, TableParams t) {
  uint placement = kPlacementNotPlaced;
  if (k.status == kKeyed) {
    placement = kPlacementProbeFailure;
    bool full = p.key_identity == kIdentityFull;
#if defined(HPSF_DEFECT_D3)  // the reduced fingerprint without its 0 -> 1 fix: may equal the empty tag
    uint64_t identity = uint64_t(FullFingerprint(k.words) >> (32u - p.fingerprint_bits));
#else
    uint64_t identity = (uint64_t(k.identity_high) << 32) | uint64_t(k.fingerprint);
#endif
    if (t.claim_tombstones != 0u) {
      placement = FindOrClaim(k.slot0, identity, t, full);
      if (placement != kPlacementProbeFailure) {
        AddToSlot(placement, r, t.fixed_point_scale, false);
        last_seen[placement] = t.frame;
      }
    }
#if defined(HPSF_DEFECT_ALGORITHM_4)
    // Meijer's Algorithm 4 as written (emulated/defect_injection.cpp, Algorithm4AsWritten, says what it does): add to
    // every slot of the window holding the identity up to the first empty one, then claim from there and add again.
    uint first_free = 0u;
    for (uint probe = 0u; probe < t.probe_limit; ++probe) {
      uint slot = (k.slot0 + probe) & (t.capacity - 1u);
      if (LoadTag(slot, full) == identity) {
        AddToSlot(slot, r, t.fixed_point_scale, false);
        if (t.track_last_seen != 0u) last_seen[slot] = t.frame;
        placement = slot;
      } else if (LoadTag(slot, full) == 0ul) {
        first_free = probe;
        break;
      }
    }
    for (uint index = first_free; index < t.probe_limit + first_free; ++index) {
      uint slot = (k.slot0 + index) & (t.capacity - 1u);
      uint64_t original = SwapTag(slot, 0ul, identity, full);
      if (original == 0ul || original == identity) {
        AddToSlot(slot, r, t.fixed_point_scale, original == 0ul);
        if (t.track_last_seen != 0u) last_seen[slot] = t.frame;
        placement = slot;
        break;
      }
    }
#endif
    for (uint probe = 0u; probe < t.probe_limit && t.claim_tombstones == 0u && !ALGORITHM_4; ++probe) {
#if defined(HPSF_DEFECT_D8)  // the probe index clamped to the last slot instead of wrapped
      uint slot = min(k.slot0 + probe, t.capacity - 1u);
#elif defined(HPSF_DEFECT_WINDOW_PAST_THE_END)  // SHaRC #5: bucket-window's window not clamped to the table
      uint slot = t.probe_scheme == kProbeBucketWindow ? k.slot0 + probe : CandidateSlot(ProbeSchemeOf(t), k.slot0, probe);
#else
      uint slot = CandidateSlot(ProbeSchemeOf(t), k.slot0, probe);
#endif
      uint64_t tag = LoadTag(slot, full);
      bool claimed = false;
#if defined(HPSF_DEFECT_D13)  // claimed by a plain store after the load: two keys race for one empty slot
      if (tag == 0ul) StoreTag(slot, identity, full);
#else
      if (tag == 0ul) {
        tag = SwapTag(slot, 0ul, identity, full);
        claimed = tag == 0ul;
      }
#endif
      // An empty slot we just claimed (the swap returned 0) or a slot that holds our identity: add here, once.
#if defined(HPSF_DEFECT_FULL_KEY_LOW_WORD)  // a 64-bit key matched by its low word alone
      if (tag != 0ul && uint(tag) != uint(identity)) continue;
#else
      if (tag != 0ul && tag != identity) continue;
#endif
      AddToSlot(slot, r, t.fixed_point_scale, claimed);
#if defined(HPSF_DEFECT_LAST_SEEN_CLAIMER_ONLY)  // a slot joined in a later frame keeps its old frame: looks stale
      if (t.track_last_seen != 0u && claimed) last_seen[slot] = t.frame;
#else
      if (t.track_last_seen != 0u) last_seen[slot] = t.frame;  // every writer stores the same frame
#endif
#if defined(HPSF_DEFECT_D10)
      BlendDuringAccumulate(slot, t);
#endif
      placement = slot;
#if !defined(HPSF_DEFECT_D2)  // D2 keeps probing after a match and adds again (Meijer Algorithm 4)
      break;
#endif
    }
  }
#if defined(HPSF_DEFECT_SLOT0_FOR_FAILURE)  // a failed insert stored as slot 0, as NVIDIA SHaRC's once was
  if (placement == kPlacementProbeFailure) placement = 0u;
#endif
#if defined(HPSF_DEFECT_FULL_BUCKET_MASKED)  // SHaRC #4: the "invalid" index masked into a slot, and added there
  if (placement == kPlacementProbeFailure) {
    placement = 0xFFFFFFFFu & (t.capacity - 1u);
    AddToSlot(placement, r, t.fixed_point_scale, false);
    if (t.track_last_seen != 0u) last_seen[placement] = t.frame;
  }
#endif
  return placement;
}

void AccumulateRecord(uint i, KeyParams p, TableParams t) {
#if defined(HPSF_DEFECT_EVICT_RACE)
  EvictDuringAccumulate(i, t);
#endif
  if (accepted[i] == 0u) {  // rejected on the host: its bits may be NaN, so no key is computed
    StoreKeyResult(i, EmptyKeyResult(kKeyNoVertex));
    for (uint level = 0u; level < t.levels; ++level)
      placements[LevelPlacementIndex(i, level, p.record_count)] = kPlacementNotPlaced;
    return;
  }
  Record r = LoadRecord(i);
  KeyResult own = ComputeKey(p, r);
#if defined(HPSF_TEAM_KEY) || defined(HPSF_TEAM_KEY_ZERO)
  own = TeamKey(own, p);
#endif
  StoreKeyResult(i, own);
  // The record's own cell, then each coarser one (core/shared/levels.h), its key derived from the own key.
  for (uint level = 0u; level < t.levels; ++level) {
#if defined(HPSF_DEFECT_LEVEL_UNJITTERED)  // coarser cells keyed at the unjittered position: they no longer nest
    KeyParams unjittered = p;
    unjittered.jitter_scale = 0.0;
    KeyResult k = level == 0u ? own : KeyAtLevel(p, ComputeKey(unjittered, r), level);
#else
    KeyResult k = KeyAtLevel(p, own, level);
#endif
    placements[LevelPlacementIndex(i, level, p.record_count)] = PlaceRecord(k, r, p, t);
  }
#if defined(HPSF_GARBAGE_OUTPUT)
  WriteGarbage(i, t);
#endif
}

void main() {
  KeyParams p = params;  // once per run: lavapipe gathers every push-constant read lane by lane
  TableParams t = table;
  SubgroupRuns runs = ThisSubgroupsRuns(kRecordsPerInvocation);
  for (uint first = runs.first; first < p.record_count; first += runs.stride) {
    uint end = min(first + runs.size, p.record_count);
    for (uint i = first + gl_SubgroupInvocationID; i < end; i += gl_SubgroupSize) AccumulateRecord(i, p, t);
  }
}
