#version 450
// Converts floats to fixed64 with core/shared/fixed_point.h, so a test can hold the device's round-half-to-even
// to the C++ result bit for bit before any accumulate pass relies on it.
#extension GL_GOOGLE_include_directive : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/fixed_point.h"

layout(local_size_x = 128) in;

layout(std430, binding = 0) readonly buffer Values { float values[]; };
layout(std430, binding = 1) writeonly buffer FixedPoint { uint64_t fixed_point[]; };
layout(push_constant) uniform Params {
  float scale;  // 2^F
  uint count;
};

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < count; i += stride) fixed_point[i] = ToFixedPoint(values[i], scale);
}
