// The per-batch choice of F, the fraction bits of fixed64 accumulation: the largest F in [-126, 126] such that,
// for every channel, the sum over all accepted vertex records of ceil(c * 2^F) stays below 2^63. Rounding never
// exceeds the ceiling, so no cell, and not even the whole table, can overflow. F goes into every report.
#ifndef HPSF_CORE_FIXED_POINT_SCALE_H
#define HPSF_CORE_FIXED_POINT_SCALE_H

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include <glm/vec3.hpp>

#include "core/error.h"
#include "core/record.h"

namespace hpsf {

// Runs work(begin, end) over disjoint ranges that cover [0, n), possibly on several threads at once. core has no
// thread pool (it depends on glm alone), so a backend passes its own; empty runs one range on the caller.
using RangeRunner =
    std::function<void(std::size_t n, const std::function<void(std::size_t begin, std::size_t end)>& work)>;

int ChooseFixedPointBits(std::span<const Record> records, std::uint32_t frames = 1);
// The same choice from the contributions of the records that enter the table; a backend that has already
// checked its records passes those, with zero in place of a record that does not enter (zero adds nothing).
// The sums are integers, so F does not depend on how the runner splits the work.
// frames > 1: a table integrated over that many frames like this one keeps the first frame's F, so
// the first frame's sums must stay below 2^63 / frames instead: frames alike never overflow, and a later,
// brighter frame that does is counted by the kernels' wrap check.
int ChooseFixedPointBitsOf(std::span<const glm::vec3> contributions, const RangeRunner& runner = {},
                           std::uint32_t frames = 1);

// Every contribution converts at F: fixed64's c * 2^F, rounded, lies below 2^64, where the conversion is defined in
// C++ and GLSL alike (a sum past it wraps and is counted; one conversion past it is undefined). The automatic F
// always fits its first frame, but a given --fixed-point-bits, or a later frame much brighter than the first, may not:
// a ConfigError naming --fixed-point-bits and the largest F that would. `contributions` as for the choice above.
// The error names --fixed-point-bits; its own type lets hpsf fuzz tell a batch hpsf cannot represent from a bug.
class FixedPointRangeError : public ConfigError {
 public:
  using ConfigError::ConfigError;
};
void RequireFixedPointConverts(std::span<const glm::vec3> contributions, int fixed_point_bits);
// The same over the records that enter the table.
void RequireFixedPointConverts(std::span<const Record> records, int fixed_point_bits);

// The channel total bound of the choice above, exact: sum of ceil(c * 2^F) over accepted vertex records.
// Saturates at 2^127 instead of wrapping.
unsigned __int128 FixedPointCeilingSum(std::span<const Record> records, int channel, int fraction_bits);

// float32 accumulation refuses a batch whose channel total reaches about 2^127, which is F < -64: below it no
// float32 cell sum can reach Inf (2^128), for a cell of fewer than 2^22 records cannot round its way there even
// if every add rounds up by 2^-23, since (1 + 2^-23)^(2^22) < 2. fixed64 takes the same batch at any F.
inline constexpr int kFloat32FixedPointBitsMin = -64;
// Throws ConfigError naming --accum when fixed_point_bits, the batch's F, is below kFloat32FixedPointBitsMin.
void RequireFloat32Range(int fixed_point_bits);

// --second-moments: G, the fraction bits of fixed64's square sums (core/shared/second_moment.h), chosen as F is: the
// largest G in [-126, 126] such that the sum of ceil(y^2 * 2^G) over the batch, y = r + g + b in double, stays below
// 2^63 / frames. float32 keeps the same G for its range check. Kept for a sequence's later frames like F.
int ChooseSquareBitsOf(std::span<const glm::vec3> contributions, const RangeRunner& runner = {},
                       std::uint32_t frames = 1);
int ChooseSquareBits(std::span<const Record> records, std::uint32_t frames = 1);
// Every square converts at G: round(y^2 * 2^G) lies below 2^64. A FixedPointRangeError naming --second-moments
// otherwise (a later frame much brighter than the one that chose G; the first always fits).
void RequireSquaresConvert(std::span<const glm::vec3> contributions, int square_bits);
void RequireSquaresConvert(std::span<const Record> records, int square_bits);
// float32 squares: a ConfigError naming --second-moments when G is below kFloat32FixedPointBitsMin, where a cell's
// float sum of squares could reach Inf.
void RequireFloat32SquaresRange(int square_bits);

// Back to a real number: value * 2^-F in double (exact below 2^53).
double FromFixedPoint(std::uint64_t value, int fraction_bits);

}  // namespace hpsf

#endif  // HPSF_CORE_FIXED_POINT_SCALE_H
