#version 450
// The accumulate pass with packed-decimal sums: 32-bit integer atomics on the sums and the count word
// (accumulate.glsl, core/shared/packed_sums.h).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#define HPSF_PACKED_DECIMAL
#define HPSF_SUMS_TYPE uint
#define HPSF_COUNT_TYPE uint
#include "accumulate.glsl"
