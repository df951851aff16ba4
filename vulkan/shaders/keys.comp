#version 450
// Computes the key of every record with core/shared/key.h: key words, slot0, fingerprint, level and status,
// written packed (core/shared/packed_key.h). Level 1 of the cross-check compares its output with the C++
// result word for word.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/packed_key.h"
#include "subgroup_runs.glsl"

#define HPSF_RECORDS_BINDING 0
#include "record_texels.glsl"

// The host dispatches ceil(n / (128 * 16)) workgroups, at most 65535 (vulkan/key_pass.cpp).
const uint kRecordsPerInvocation = 16u;
layout(local_size_x = 128) in;

layout(std430, binding = 1) writeonly buffer Keys { uvec4 packed_keys[]; };  // two vectors per record
layout(push_constant) uniform Params { KeyParams params; };

void main() {
  KeyParams p = params;  // once per run: lavapipe gathers every push-constant read lane by lane
  SubgroupRuns runs = ThisSubgroupsRuns(kRecordsPerInvocation);
  for (uint first = runs.first; first < p.record_count; first += runs.stride) {
    uint end = min(first + runs.size, p.record_count);
    for (uint i = first + gl_SubgroupInvocationID; i < end; i += gl_SubgroupSize) {
      KeyResult k = ComputeKey(p, LoadRecord(i));
      packed_keys[2u * i] = PackedKeyCell(k);
      packed_keys[2u * i + 1u] = PackedKeyHashes(k);
    }
  }
}
