#version 450
// The resolve's second pass, the neighbourhood search over the pixels the first pass listed, with float32 sums (resolve.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_spirv_intrinsics : require
#define HPSF_SUMS_TYPE float
#define HPSF_SEARCH_DEFERRED_PIXELS
#include "resolve.glsl"
