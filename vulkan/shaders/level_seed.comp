#version 450
// The seed pass of resolution changes (core/level_seed.h; the emulator's emulated/level_seed_kernel.h holds the
// rule): one invocation per record, after the accumulate and before the temporal blend. A record placed in a slot
// that held no samples before the frame claims the slot's seeding (compare-and-swap of its flag, 0 to 1), computes
// its cell's seed from the table before the frame (the double buffer the host copied before the accumulate: tags,
// sums, counts; no pass of the frame writes it) by core/shared/level_seed.h, adds it, and marks the flag 2. Only
// the claiming invocation writes the slot in this pass, so its adds need no atomics.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/full_key.h"
#include "../../core/shared/level_seed.h"
#include "../../core/shared/lookup.h"
#include "../../core/shared/packed_sums.h"
#include "../../core/shared/probe_scheme.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Keys { uvec4 key_vectors[]; };  // the accumulate's binding 1
layout(std430, binding = 1) readonly buffer Placements { uint placements[]; };
layout(std430, binding = 2) buffer SumWords { uint sum_words[]; };  // the sums, as 32-bit words
layout(std430, binding = 3) buffer Counts { uint64_t counts[]; };
layout(std430, binding = 3) buffer CountWords { uint count_words[]; };  // the same buffer, with packed
// The table before the frame's tags, read through slot_tags.glsl as 32-bit fingerprints or 64-bit full keys.
layout(std430, binding = 4) readonly buffer PreviousTags { uint tags[]; };
layout(std430, binding = 4) readonly buffer PreviousFullTags { uint64_t full_tags[]; };
layout(std430, binding = 5) readonly buffer PreviousSumWords { uint previous_sum_words[]; };
layout(std430, binding = 6) readonly buffer PreviousCounts { uint64_t previous_counts[]; };
layout(std430, binding = 6) readonly buffer PreviousCountWords { uint previous_count_words[]; };  // with packed
layout(std430, binding = 7) buffer Seeded { uint seeded[]; };  // per slot, zeroed: 1 claimed, 2 seeded
layout(std430, binding = 8) buffer SeededCount { uint64_t seeded_count; };
layout(push_constant) uniform Params {  // vulkan_filter.cpp's LevelSeedPush
  uint capacity;
  uint probe_limit;
  uint fingerprint_bits;
  uint normal_in_index;
  uint shift;    // S of seed:S
  uint fixed64;  // 1: sums are 64-bit fixed point (two words per channel); 0: float32 or packed-decimal
  uint record_count;
  uint probe_scheme;  // kProbeLinear, kProbeBucket or kProbeBucketWindow
  uint key_identity;  // kIdentityFingerprint or kIdentityFull (core/shared/full_key.h)
  uint packed;        // 1: packed-decimal, 32-bit integer sums and count words (core/shared/packed_sums.h)
  uint levels;        // --levels: placements hold levels words per record, level-major (core/shared/levels.h)
  uint reserved;
};

// A slot's samples before the frame: packed-decimal's count bits, without the frame counter.
uint64_t PreviousCount(uint slot) {
  return packed != 0u ? uint64_t(PackedCount(previous_count_words[slot])) : previous_counts[slot];
}
#define HPSF_TAGS_READONLY
#include "slot_tags.glsl"

struct Neighbour {
  bool found;
  uint64_t count;
  uint64_t fixed_sum[3];
  float float_sum[3];
};

// The first slot of the words' window in the table before the frame holding their identity with samples, up to
// the first empty slot (core/level_seed.cpp's FindInTable). Words beyond a full key's range are in no slot.
Neighbour Find(KeyWords words) {
  Neighbour n;
  n.found = false;
  n.count = 0ul;
  StoredIdentity identity = IdentityOfWords(words, key_identity, fingerprint_bits);
  if (!identity.fits) return n;
  uint slot0 = IndexHash(words, normal_in_index) & (capacity - 1u);
  uint64_t wanted = IdentityValue(identity.words);
  bool full = key_identity == kIdentityFull;
  ProbeScheme scheme = MakeProbeScheme(probe_scheme, capacity, probe_limit);
  for (uint probe = 0u; probe < probe_limit; ++probe) {
    uint slot = CandidateSlot(scheme, slot0, probe);
    uint step = LookupStep(LoadTag(slot, full), wanted, PreviousCount(slot));
    if (step == kLookupEnd) break;
    if (step == kLookupNext) continue;
    n.found = true;
    n.count = PreviousCount(slot);
    for (uint c = 0u; c < 3u; ++c) {
      uint w = slot * 3u + c;
      n.fixed_sum[c] = fixed64 != 0u  ? (uint64_t(previous_sum_words[2u * w]) |
                                         (uint64_t(previous_sum_words[2u * w + 1u]) << 32))
                       : packed != 0u ? uint64_t(previous_sum_words[w])
                                      : 0ul;
      n.float_sum[c] = fixed64 != 0u || packed != 0u ? 0.0 : uintBitsToFloat(previous_sum_words[w]);
    }
    return n;
  }
  return n;
}

// Touch t: record t mod n at t / n levels above its own cell (core/shared/levels.h).
void Seed(uint t) {
  uint i = t % record_count;
  uint slot = placements[t];
  if (slot >= capacity || PreviousCount(slot) != 0ul) return;  // not placed, or not new
  if (atomicCompSwap(seeded[slot], 0u, 1u) != 0u) return;       // another record seeds it
  uvec4 v0 = key_vectors[i * 3u], v1 = key_vectors[i * 3u + 1u];
  KeyWords cell;
  cell.cell_x = v0.x;
  cell.cell_y = v0.y;
  cell.cell_z = v0.z;
  cell.level = v0.w;
  cell.normal = v1.x;
  cell.extra = v1.y;
  cell = CoarserKeyWords(cell, t / record_count);
  // SeedOf: the children's sums where any child holds samples, else the parent's share.
  uint64_t count = 0ul;
  uint64_t fixed_sum[3] = uint64_t[3](0ul, 0ul, 0ul);
  float float_sum[3] = float[3](0.0, 0.0, 0.0);
  for (uint child = 0u; child < kLevelSeedChildren; ++child) {
    Neighbour n = Find(ChildKeyWords(cell, child));
    if (!n.found) continue;
    count += n.count;
    for (uint c = 0u; c < 3u; ++c) {
      fixed_sum[c] += n.fixed_sum[c];
      float_sum[c] += n.float_sum[c];
    }
  }
  if (count == 0ul) {
    Neighbour parent = Find(ParentKeyWords(cell));
    if (!parent.found) return;
    count = ParentShareOfCount(parent.count, shift);
    if (count == 0ul) return;  // too few samples to share
    for (uint c = 0u; c < 3u; ++c) {
      fixed_sum[c] = ParentShareOfFixedSum(parent.fixed_sum[c], shift);
      float_sum[c] = ParentShareOfFloatSum(parent.float_sum[c], shift);
    }
  }
  for (uint c = 0u; c < 3u; ++c) {
    uint w = slot * 3u + c;
    if (fixed64 != 0u) {
      uint64_t sum = (uint64_t(sum_words[2u * w]) | (uint64_t(sum_words[2u * w + 1u]) << 32)) + fixed_sum[c];
      sum_words[2u * w] = uint(sum);
      sum_words[2u * w + 1u] = uint(sum >> 32);
    } else if (packed != 0u) {  // a 32-bit word, wrapping as the accumulate's adds do
      sum_words[w] += uint(fixed_sum[c]);
    } else {
      sum_words[w] = floatBitsToUint(uintBitsToFloat(sum_words[w]) + float_sum[c]);
    }
  }
  if (packed != 0u) {  // the count bits, carrying into the frame counter as a record's add does
    count_words[slot] += uint(count);
  } else {
    counts[slot] += count;
  }
  seeded[slot] = 2u;
  atomicAdd(seeded_count, 1ul);
}

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint t = gl_GlobalInvocationID.x; t < record_count * levels; t += stride) Seed(t);
}
