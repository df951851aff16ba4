#version 450
// The resolve's second pass, the neighbourhood search over the pixels the first pass listed, with packed-decimal sums and count words (resolve.glsl, core/shared/packed_sums.h).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_spirv_intrinsics : require
#define HPSF_PACKED_DECIMAL
#define HPSF_SUMS_TYPE uint
#define HPSF_COUNT_TYPE uint
#define HPSF_SEARCH_DEFERRED_PIXELS
#include "resolve.glsl"
