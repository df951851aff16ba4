#version 450
// The resolve pass over fixed64 sums (resolve.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_spirv_intrinsics : require
#define HPSF_FIXED64
#define HPSF_SUMS_TYPE uint64_t
#include "resolve.glsl"
