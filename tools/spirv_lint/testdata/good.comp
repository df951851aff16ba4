#version 450
// spirv_lint test case: good.
#extension GL_GOOGLE_include_directive : require
#include "../../../vulkan/shaders/float_controls.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Data { float values[]; };
void main() {
  float x = values[gl_GlobalInvocationID.x];
  precise float y = x * 3.0f + 1.0f;
  values[gl_GlobalInvocationID.x] = y;
}
