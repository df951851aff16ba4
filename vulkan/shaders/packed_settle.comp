#version 450
// packed-decimal's settle after a frame's accumulate (core/shared/packed_sums.h; the emulator's
// emulated/packed_settle_kernel.h): one invocation per slot, or per entry of the occupied list. A slot with samples
// advances its frame counter and is halved where its count or a sum passed the layout's bound, by the function
// C++ runs. A pass of its own, after every add of the frame has landed.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "../../core/shared/prelude.h"
#include "../../core/shared/packed_sums.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Sums { uint sums[]; };      // slot * 3 + c
layout(std430, binding = 1) buffer Counts { uint counts[]; };  // the count word
layout(std430, binding = 2) buffer Halved { uint64_t halved; };
// Bindings 3 and 4, with --compaction occupied-list (compacted): one invocation per entry of the list.
layout(std430, binding = 3) readonly buffer Occupied { uint occupied[]; };
layout(std430, binding = 4) readonly buffer OccupiedHeader { uint occupied_count; };
layout(push_constant) uniform Params {  // vulkan_filter.cpp's SettlePush
  uint capacity;
  uint compacted;  // 1: dispatched indirectly, one invocation per entry of the occupied list (core/compaction.h)
};

void Settle(uint slot) {
  uint word = counts[slot];
  if (PackedCount(word) == 0u) return;  // empty, or a tombstone
  uvec4 cell = uvec4(sums[slot * 3u], sums[slot * 3u + 1u], sums[slot * 3u + 2u], word);
  bool halving = PackedNeedsHalving(cell);
  uvec4 settled = SettlePacked(cell);
  if (halving) {
    for (uint c = 0u; c < 3u; ++c) sums[slot * 3u + c] = settled[c];
    atomicAdd(halved, 1ul);
  }
  counts[slot] = settled.w;
}

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  uint steps = compacted != 0u ? occupied_count : capacity;
  for (uint step = gl_GlobalInvocationID.x; step < steps; step += stride) Settle(compacted != 0u ? occupied[step] : step);
}
