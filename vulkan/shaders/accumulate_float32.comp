#version 450
// The accumulate pass with float32 sums: float atomic adds, whose order the device decides (accumulate.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_float : require
#extension GL_EXT_shader_atomic_int64 : require
#define HPSF_SUMS_TYPE float
#include "accumulate.glsl"
