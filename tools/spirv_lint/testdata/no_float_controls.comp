#version 450
// spirv_lint test case: no_float_controls.
#extension GL_GOOGLE_include_directive : require
// no float controls declared
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Data { float values[]; };
void main() {
  float x = values[gl_GlobalInvocationID.x];
  precise float y = x * 3.0f + 1.0f;
  values[gl_GlobalInvocationID.x] = y;
}
