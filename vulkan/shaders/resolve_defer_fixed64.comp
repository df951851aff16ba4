#version 450
// The resolve's first pass with --neighbour-search on, which lists the pixels whose records search, over fixed64 sums (resolve.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_spirv_intrinsics : require
#define HPSF_FIXED64
#define HPSF_SUMS_TYPE uint64_t
#define HPSF_DEFER_SEARCH
#include "resolve.glsl"
