#version 450
// The resolve pass with the neighbourhood search over fixed64 sums (resolve.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_spirv_intrinsics : require
#define HPSF_FIXED64
#define HPSF_SUMS_TYPE uint64_t
#define HPSF_NEIGHBOUR_SEARCH
#include "resolve.glsl"
