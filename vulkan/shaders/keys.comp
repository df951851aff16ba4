#version 450
// Computes the key of every record with core/shared/key.h: key words, slot0, fingerprint, level and status.
// Level 1 of the cross-check compares its output with the C++ result word for word.
#extension GL_GOOGLE_include_directive : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/key.h"

#define HPSF_RECORDS_BINDING 0
#include "record_texels.glsl"

layout(local_size_x = 128) in;

// KeyResult as three uvec4 each: one store per vector instead of one per word.
layout(std430, binding = 1) writeonly buffer Keys { uvec4 key_vectors[]; };
layout(push_constant) uniform Params { KeyParams params; };

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < params.record_count; i += stride) {
    KeyResult k = ComputeKey(params, LoadRecord(i));
    uint first = i * 3u;
    key_vectors[first] = uvec4(k.words.cell_x, k.words.cell_y, k.words.cell_z, k.words.level);
    key_vectors[first + 1u] = uvec4(k.words.normal, k.words.extra, k.slot0, k.fingerprint);
    key_vectors[first + 2u] = uvec4(uint(k.level), k.status, k.padding0, k.padding1);
  }
}
