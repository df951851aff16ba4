#version 450
// The resolve pass with the neighbourhood search over float32 sums (resolve.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_spirv_intrinsics : require
#define HPSF_SUMS_TYPE float
#define HPSF_NEIGHBOUR_SEARCH
#include "resolve.glsl"
