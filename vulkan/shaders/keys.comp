#version 450
// Computes the key of every record with core/shared/key.h: key words, slot0, fingerprint, level and status.
// Level 1 of the cross-check compares its output with the C++ result word for word.
#extension GL_GOOGLE_include_directive : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/key.h"

layout(local_size_x = 128) in;

layout(std430, binding = 0) readonly buffer Records { Record records[]; };
layout(std430, binding = 1) writeonly buffer Keys { KeyResult keys[]; };
layout(push_constant) uniform Params { KeyParams params; };

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < params.record_count; i += stride) {
    keys[i] = ComputeKey(params, records[i]);
  }
}
