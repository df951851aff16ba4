// The small prelude that lets core/shared/ compile both as C++ (through glm, which mirrors GLSL) and as
// GLSL 4.50. Everything in core/shared/ is written in the common subset: GLSL syntax, glm types and
// functions, no references, no templates; functions are HPSF_FN and key-path values HPSF_PRECISE.
#ifndef HPSF_CORE_SHARED_PRELUDE_H
#define HPSF_CORE_SHARED_PRELUDE_H

#ifndef __cplusplus  // GLSL: the shader includes this first, right after #version and its #extension lines.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#define HPSF_FN
#define HPSF_PRECISE precise
#define HPSF_SHARED_BEGIN
#define HPSF_SHARED_END
#define HPSF_ROUND_EVEN(x) roundEven(x)
#define HPSF_SIGNED_ZERO(x) uintBitsToFloat(floatBitsToUint(x) & 0x80000000u)

#else  // C++
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#define HPSF_FN inline __attribute__((always_inline))  // inlining the whole key path doubles its speed at -O2
#define HPSF_PRECISE
#define HPSF_SHARED_BEGIN  \
  namespace hpsf::shared { \
  using namespace glm;
#define HPSF_SHARED_END }
// std::nearbyint rounds half to even in the default rounding mode, as GLSL's roundEven does; glm's roundEven
// goes through integer conversions that are wrong above 2^31.
#define HPSF_ROUND_EVEN(x) std::nearbyint(x)
// The zero with x's sign. The same bits as GLSL's mask of the sign bit, but it stays in an SSE register: GCC
// otherwise carries Flush's result through an integer register, and the round trip lengthened the key path's
// dependency chain enough to cost C++ keys 15% (measured side by side in keys_benchmark).
#define HPSF_SIGNED_ZERO(x) std::copysign(0.0f, x)

namespace hpsf::shared {
using uint = std::uint32_t;
using std::int64_t;
using std::uint64_t;

// GLSL's abs clears the sign bit (abs(-0.0) is +0.0); glm's is x >= 0 ? x : -x, which keeps -0.0 and costs a
// compare and a blend where fabs is one and (C++ keys 10-20% faster, measured side by side).
inline float abs(float x) { return std::fabs(x); }
inline glm::vec3 abs(glm::vec3 v) { return glm::vec3(std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)); }
}  // namespace hpsf::shared
#endif

#endif  // HPSF_CORE_SHARED_PRELUDE_H
