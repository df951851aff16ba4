#version 450
// Compaction into a list of occupied slots (core/compaction.h; the emulator's emulated/compaction_kernels.h holds the
// same passes). Pass 0, gather, one invocation per record after the accumulate: a placed record that is the first
// to set its slot's flag appends the slot at the list's count. Pass 1, prune, one invocation per entry after the
// reclaim: an entry whose slot is occupied is appended to the next list, one the reclaim emptied clears its flag.
// Pass 2, one invocation: the next list's count becomes the list's (the host then swaps the two lists' buffers).
// Pass 3, one invocation: the indirect dispatch of the passes over the list, one invocation per entry, 64 to a
// workgroup (their loops stride over the rest where the count passes 65535 workgroups).
// The test suite compiles this file once more per defect: HPSF_DEFECT_COUNT_ONE_WHEN_EMPTY, pass 2 counts one entry
// where the prune kept none (Bevy #21904).
#extension GL_GOOGLE_include_directive : require
#include "../../core/shared/prelude.h"
#include "../../core/shared/table_params.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Placements { uint placements[]; };
layout(std430, binding = 1) readonly buffer Tags { uint tags[]; };
layout(std430, binding = 1) readonly buffer FullTags { uint64_t full_tags[]; };  // the same buffer, with full_keys
layout(std430, binding = 2) buffer Listed { uint listed[]; };  // per slot: 1 while in the list
layout(std430, binding = 3) buffer Occupied { uint occupied[]; };
layout(std430, binding = 4) buffer Header {
  uint count;  // the list's length
  // The VkDispatchIndirectCommand of the passes over the list, at byte 4 (three uints, not a uvec3: std430 would
  // align that to 16).
  uint groups_x;
  uint groups_y;
  uint groups_z;
  uint next_count;  // the prune's output count
};
layout(std430, binding = 5) buffer NextOccupied { uint next_occupied[]; };
layout(push_constant) uniform Params {  // vulkan_filter.cpp's CompactionPush
  uint pass;  // 0 gather, 1 prune, 2 finish the prune, 3 the dispatch
  uint record_count;
  uint capacity;
  uint full_keys;  // 1 with --key-identity full: 64-bit tags (slot_tags.glsl)
};
#define HPSF_TAGS_READONLY
#include "slot_tags.glsl"

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  if (pass == 0u) {
    for (uint i = gl_GlobalInvocationID.x; i < record_count; i += stride) {
      uint slot = placements[i];
      if (slot >= capacity) continue;  // not placed
      // A plain read first: most records join a slot listed already, and a flag only goes from 0 to 1 in this pass.
      if (listed[slot] != 0u) continue;
      if (atomicCompSwap(listed[slot], 0u, 1u) != 0u) continue;
      occupied[atomicAdd(count, 1u)] = slot;
    }
  } else if (pass == 1u) {
    for (uint entry = gl_GlobalInvocationID.x; entry < count; entry += stride) {
      uint slot = occupied[entry];
      if (LoadTag(slot, full_keys != 0u) == 0ul) {
        listed[slot] = 0u;
      } else {
        next_occupied[atomicAdd(next_count, 1u)] = slot;
      }
    }
  } else if (gl_GlobalInvocationID.x == 0u) {
    if (pass == 2u) {
#if defined(HPSF_DEFECT_COUNT_ONE_WHEN_EMPTY)
      count = max(next_count, 1u);
#else
      count = next_count;
#endif
      next_count = 0u;
    } else {
      groups_x = min((count + 63u) / 64u, 65535u);
      groups_y = 1u;
      groups_z = 1u;
    }
  }
}
