#version 450
// The resolve pass over float32 sums (resolve.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_spirv_intrinsics : require
#define HPSF_SUMS_TYPE float
#include "resolve.glsl"
