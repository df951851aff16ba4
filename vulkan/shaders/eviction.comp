#version 450
// The eviction pass after a frame's accumulate (core/eviction.h; the emulator's emulated/eviction_kernels.h holds
// the rule and why tombstones): one invocation per slot, dispatched twice with a barrier between. Pass 0, evict:
// a live slot last seen `unseen_frames` or more frames ago keeps its tag and becomes a tombstone (count and sums
// zeroed). Pass 1, reclaim: a tombstone is emptied unless a live slot follows it within probe_limit - 1 slots with
// no empty slot between. The test suite compiles HPSF_DEFECT_D7 once more: the reclaim empties every tombstone.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Tags { uint tags[]; };
layout(std430, binding = 1) buffer SumWords { uint sum_words[]; };  // fixed64 or float32 sums, as 32-bit words
layout(std430, binding = 2) buffer Counts { uint64_t counts[]; };
layout(std430, binding = 3) readonly buffer LastSeen { uint last_seen[]; };
layout(std430, binding = 4) buffer Evicted { uint64_t evicted; };
layout(push_constant) uniform Params {
  uint capacity;
  uint probe_limit;
  uint frame;
  uint unseen_frames;
  uint sum_words_per_slot;  // 6 (fixed64) or 3 (float32)
  uint pass;                // 0 evict, 1 reclaim
};

void Evict(uint slot) {
  if (tags[slot] == 0u || counts[slot] == 0ul) return;
  if (frame - last_seen[slot] < unseen_frames) return;
  for (uint w = 0u; w < sum_words_per_slot; ++w) sum_words[slot * sum_words_per_slot + w] = 0u;
  counts[slot] = 0ul;
  atomicAdd(evicted, 1ul);
}

void Reclaim(uint slot) {
  if (tags[slot] == 0u || counts[slot] != 0ul) return;
#if !defined(HPSF_DEFECT_D7)  // D7 empties every tombstone: a hole on a live slot's probe path
  uint reach = min(probe_limit, capacity);
  for (uint distance = 1u; distance < reach; ++distance) {
    uint next = (slot + distance) & (capacity - 1u);
    if (tags[next] == 0u) break;
    if (counts[next] != 0ul) return;  // a live slot may have probed past this one: keep the tombstone
  }
#endif
  tags[slot] = 0u;
}

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint slot = gl_GlobalInvocationID.x; slot < capacity; slot += stride) {
    if (pass == 0u) {
      Evict(slot);
    } else {
      Reclaim(slot);
    }
  }
}
