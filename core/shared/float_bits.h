// Exact float tools built from bit operations: IEEE-754 binary32 fields, powers of two without exp2, and the
// explicit flush of denormals that makes key arithmetic independent of a device's denormal mode.
#ifndef HPSF_CORE_SHARED_FLOAT_BITS_H
#define HPSF_CORE_SHARED_FLOAT_BITS_H

#include "prelude.h"

HPSF_SHARED_BEGIN

const uint kSignBit = 0x80000000u;
const uint kExponentMask = 0x7F800000u;
const int kExponentBias = 127;
const int kMinLevel = -126;  // 2^l and 2^-l are both normal floats inside [kMinLevel, kMaxLevel].
const int kMaxLevel = 126;

// True for +-Inf and NaN: the exponent field is all ones.
HPSF_FN bool IsNonFinite(float x) { return (floatBitsToUint(x) & kExponentMask) == kExponentMask; }

// True when the sign bit is set on a value other than -0.
HPSF_FN bool IsNegative(float x) { return floatBitsToUint(x) > kSignBit; }

// Vulkan leaves denormal handling to the device unless it supports DenormPreserve (lavapipe does not). Every
// key-path result passes through Flush, which turns a denormal into the zero of its sign, so the result is the
// same whether or not the device flushed it already.
HPSF_FN float Flush(float x) { return (floatBitsToUint(x) & kExponentMask) == 0u ? HPSF_SIGNED_ZERO(x) : x; }
HPSF_FN vec3 Flush(vec3 v) { return vec3(Flush(v.x), Flush(v.y), Flush(v.z)); }

// The unbiased exponent l with 2^l <= |x| < 2^(l+1); zero and denormals report kExponentBias below the minimum
// (-127) and Inf/NaN report 128, so a clamp sends them to the ends of any level range.
HPSF_FN int UnbiasedExponent(float x) { return int((floatBitsToUint(x) & kExponentMask) >> 23u) - kExponentBias; }

// 2^l built from bits; l must lie in [-126, 127].
HPSF_FN float PowerOfTwo(int l) { return uintBitsToFloat(uint(l + kExponentBias) << 23u); }

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_FLOAT_BITS_H
