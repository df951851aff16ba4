#version 450
// The eviction pass after a frame's accumulate (core/eviction.h; the emulator's emulated/eviction_kernels.h holds
// the rule and why tombstones): one invocation per slot (or per entry of the occupied list, core/compaction.h),
// dispatched twice with a barrier between. Pass 0, evict:
// a live slot last seen `unseen_frames` or more frames ago keeps its tag and becomes a tombstone (count and sums
// zeroed). Pass 1, reclaim: a tombstone is emptied unless a live slot follows it in some key's candidate order
// (core/shared/probe_scheme.h's SlotAfter) with no empty slot between. Priority eviction (by_priority) dispatches pass 2, select, first: one invocation per record;
// a record that found no slot marks the untouched live slot of lowest priority in its window as a victim
// (core/shared/eviction_priority.h; the table is only read, so the victims do not depend on the invocations'
// order), and pass 0 evicts exactly the victims, tagging them kTombstoneTag, which an insertion may claim.
// The test suite compiles this file once more per defect: HPSF_DEFECT_D7, the reclaim empties every tombstone;
// HPSF_DEFECT_PRIORITY_SIGN, the selection's compare of the wrong sign.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "../../core/shared/prelude.h"
#include "../../core/shared/eviction_priority.h"
#include "../../core/shared/level_seed.h"
#include "../../core/shared/packed_sums.h"
#include "../../core/shared/table_params.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Tags { uint tags[]; };
layout(std430, binding = 0) buffer FullTags { uint64_t full_tags[]; };  // the same buffer, with full_keys
layout(std430, binding = 1) buffer SumWords { uint sum_words[]; };  // the sums, as 32-bit words
layout(std430, binding = 2) buffer Counts { uint64_t counts[]; };
layout(std430, binding = 2) buffer CountWords { uint count_words[]; };  // the same buffer, with packed_counts
layout(std430, binding = 3) readonly buffer LastSeen { uint last_seen[]; };
layout(std430, binding = 4) buffer Evicted { uint64_t evicted; };
// Bindings 5 to 7 are read and written by priority eviction only.
layout(std430, binding = 5) readonly buffer Keys { uvec4 key_vectors[]; };  // the accumulate's binding 1
layout(std430, binding = 6) readonly buffer Placements { uint placements[]; };
layout(std430, binding = 7) buffer Victims { uint victims[]; };  // per slot, zeroed: 1 marks a victim
// Bindings 8 and 9, with --compaction occupied-list (compacted): passes 0 and 1 step the list's entries.
layout(std430, binding = 8) readonly buffer Occupied { uint occupied[]; };
layout(std430, binding = 9) readonly buffer OccupiedHeader { uint occupied_count; };
// Binding 10, with --second-moments: the square sums (core/shared/second_moment.h), as 32-bit words.
layout(std430, binding = 10) buffer SquareWords { uint square_words[]; };
layout(push_constant) uniform Params {
  uint capacity;
  uint probe_limit;
  uint frame;
  uint unseen_frames;
  uint sum_words_per_slot;  // 6 (fixed64) or 3 (float32, packed-decimal)
  uint pass;                // 0 evict, 1 reclaim, 2 select (priority only, first)
  uint record_count;
  uint by_priority;         // 1 with --eviction priority
  uint probe_scheme;        // kProbeLinear, kProbeBucket or kProbeBucketWindow
  uint compacted;           // 1: dispatched indirectly, one invocation per entry of the occupied list
  uint full_keys;           // 1 with --key-identity full: 64-bit tags (slot_tags.glsl)
  uint packed_counts;       // 1 with packed-decimal: 32-bit count words (core/shared/packed_sums.h)
  uint levels;              // --levels: the select pass runs per record and level (core/shared/levels.h)
  uint normal_in_index;     // the key's, for a coarser level's slot0
  uint square_words_per_slot;  // --second-moments: 2 (fixed64) or 1 (float32); 0 without
  uint reserved;
};

// packed-decimal's whole count word, as the emulator's eviction kernels read it: a live cell's is never 0 (its count
// halves up), a tombstone's is.
uint64_t CountAt(uint slot) { return packed_counts != 0u ? uint64_t(count_words[slot]) : counts[slot]; }
// The samples a slot holds, which priority compares: packed-decimal's count bits, without the frame counter.
uint64_t SampleCount(uint slot) { return packed_counts != 0u ? uint64_t(PackedCount(count_words[slot])) : counts[slot]; }
// The whole count word: an evicted cell's frame counter starts again.
void ClearCount(uint slot) {
  if (packed_counts != 0u) {
    count_words[slot] = 0u;
  } else {
    counts[slot] = 0ul;
  }
}
#include "slot_tags.glsl"

ProbeScheme Scheme() { return MakeProbeScheme(probe_scheme, capacity, probe_limit); }

// Touch t: record t mod n at t / n levels above its own cell (core/shared/levels.h).
void SelectVictim(uint t) {
  if (placements[t] != kPlacementProbeFailure) return;
  uint i = t % record_count;
  uint slot0 = key_vectors[i * 3u + 1u].z;
  if (t >= record_count) {
    uvec4 v0 = key_vectors[i * 3u], v1 = key_vectors[i * 3u + 1u];
    KeyWords own;
    own.cell_x = v0.x;
    own.cell_y = v0.y;
    own.cell_z = v0.z;
    own.level = v0.w;
    own.normal = v1.x;
    own.extra = v1.y;
    slot0 = Slot0AtLevel(own, t / record_count, normal_in_index, capacity - 1u);
  }
  bool found = false;
  uint victim = 0u;
  uint64_t victim_tag = 0ul;
  uint64_t victim_priority = 0ul;
  for (uint probe = 0u; probe < probe_limit; ++probe) {
    uint slot = CandidateSlot(Scheme(), slot0, probe);
    uint64_t tag = LoadTag(slot, full_keys != 0u);
    if (tag == 0ul || tag == uint64_t(kTombstoneTag)) continue;
    uint64_t count = SampleCount(slot);
    if (count == 0ul || last_seen[slot] == frame) continue;  // a tombstone of another policy, or touched this frame
    uint64_t priority = EvictionPriority(last_seen[slot], count);
#if defined(HPSF_DEFECT_PRIORITY_SIGN)  // the compare's operands swapped: the highest priority is evicted
    if (!found || EvictedBefore(victim_priority, victim_tag, priority, tag)) {
#else
    if (!found || EvictedBefore(priority, tag, victim_priority, victim_tag)) {
#endif
      found = true;
      victim = slot;
      victim_priority = priority;
      victim_tag = tag;
    }
  }
  if (found) victims[victim] = 1u;
}

void Evict(uint slot) {
  if (LoadTag(slot, full_keys != 0u) == 0ul || CountAt(slot) == 0ul) return;
  if (by_priority != 0u) {
    if (victims[slot] == 0u) return;
  } else if (frame - last_seen[slot] < unseen_frames) {
    return;
  }
  for (uint w = 0u; w < sum_words_per_slot; ++w) sum_words[slot * sum_words_per_slot + w] = 0u;
  for (uint w = 0u; w < square_words_per_slot; ++w) square_words[slot * square_words_per_slot + w] = 0u;
  ClearCount(slot);
  if (by_priority != 0u) StoreTag(slot, uint64_t(kTombstoneTag), full_keys != 0u);
  atomicAdd(evicted, 1ul);
}

void Reclaim(uint slot) {
  bool full = full_keys != 0u;
  if (LoadTag(slot, full) == 0ul || CountAt(slot) != 0ul) return;
#if !defined(HPSF_DEFECT_D7)  // D7 empties every tombstone: a hole on a live slot's probe path
  for (uint distance = 1u; distance < probe_limit; ++distance) {
    uint next = SlotAfter(Scheme(), slot, distance);
    if (next == kNoCandidate || LoadTag(next, full) == 0ul) break;
    if (CountAt(next) != 0ul) return;  // a live slot may have probed past this one: keep the tombstone
  }
#endif
  StoreTag(slot, 0ul, full);
}

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  if (pass == 2u) {
    for (uint t = gl_GlobalInvocationID.x; t < record_count * levels; t += stride) SelectVictim(t);
    return;
  }
  uint steps = compacted != 0u ? occupied_count : capacity;
  for (uint step = gl_GlobalInvocationID.x; step < steps; step += stride) {
    uint slot = compacted != 0u ? occupied[step] : step;
    if (pass == 0u) {
      Evict(slot);
    } else {
      Reclaim(slot);
    }
  }
}
