#version 450
// The accumulate pass with fixed64 sums: unsigned 64-bit integer atomics (accumulate.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#define HPSF_FIXED64
#define HPSF_SUMS_TYPE uint64_t
#include "accumulate.glsl"
