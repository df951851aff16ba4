#version 450
// Computes the key of every record with core/shared/key.h: key words, slot0, fingerprint, level and status,
// written packed (core/shared/packed_key.h). Level 1 of the cross-check compares its output with the C++
// result word for word.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/packed_key.h"

#define HPSF_RECORDS_BINDING 0
#include "record_texels.glsl"

// The host dispatches ceil(n / (kWorkgroupSize * kRecordsPerInvocation)) workgroups (vulkan/key_pass.cpp).
const uint kWorkgroupSize = 128u;
const uint kRecordsPerInvocation = 16u;
layout(local_size_x = kWorkgroupSize) in;

layout(std430, binding = 1) writeonly buffer Keys { uvec4 packed_keys[]; };  // two vectors per record
layout(push_constant) uniform Params { KeyParams params; };

void main() {
  // Read once: lavapipe gathers push constants lane by lane, and not hoisted they cost a tenth of the time.
  KeyParams p = params;
  // Each subgroup walks its own contiguous run of records, a subgroup-wide step at a time, so a SIMD CPU
  // device reads and writes memory in sequence (1.2x faster on lavapipe than a workgroup-wide step).
  uint subgroup = gl_WorkGroupID.x * gl_NumSubgroups + gl_SubgroupID;
  uint run = gl_SubgroupSize * kRecordsPerInvocation;
  for (uint first = subgroup * run; first < p.record_count; first += gl_NumWorkGroups.x * gl_NumSubgroups * run) {
    uint end = min(first + run, p.record_count);
    for (uint i = first + gl_SubgroupInvocationID; i < end; i += gl_SubgroupSize) {
      KeyResult k = ComputeKey(p, LoadRecord(i));
      packed_keys[2u * i] = PackedKeyCell(k);
      packed_keys[2u * i + 1u] = PackedKeyHashes(k);
    }
  }
}
