// How a slot keeps its sums and count (`--accum`, a declaration's `sums.encoding`):
// - fixed64: three 64-bit integer sums at 2^F, the count in 64 bits (core/fixed_point_scale.h chooses F);
// - float32: three float sums, the count in 64 bits;
// - packed-decimal: NVIDIA SHaRC's layout, three 32-bit integer sums at 1000 and the count packed with a frame
//   counter into a fourth word, kept in range by the settle's halving rule (core/shared/packed_sums.h).
// fixed64 and packed-decimal are integer sums: a record adds its channel times the scale rounded half to even,
// the same bits on every backend, which the checker and the contract replay exactly.
#ifndef HPSF_CORE_ACCUMULATION_H
#define HPSF_CORE_ACCUMULATION_H

#include <cstdint>
#include <span>
#include <string>

#include <glm/vec3.hpp>

#include "core/record.h"

namespace hpsf {

enum class Accumulation { kFixed64, kFloat32, kPackedDecimal };

// Parses "fixed64", "float32" or "packed-decimal"; a ConfigError naming --accum otherwise.
Accumulation ParseAccumulation(const std::string& text);
std::string ToString(Accumulation accumulation);

// fixed64 and packed-decimal: sums of integers, exact.
inline bool IntegerSums(Accumulation accumulation) { return accumulation != Accumulation::kFloat32; }

// The scale a record's channel is multiplied by before rounding: 2^F for fixed64, 1000 for packed-decimal. float32
// does not round, but the checker still forms its records' fixed-point values, at the 2^F of its range check, which
// keeps every one of them convertible: 2^F for float32 too.
float SumScale(Accumulation accumulation, int fixed_point_bits);
// An integer sum back to a real number, in double: sum * 2^-F (exact), or sum / 1000 (correctly rounded), as every
// backend's resolve computes it.
double IntegerSumValue(std::uint64_t sum, Accumulation accumulation, int fixed_point_bits);

// Every contribution of a packed-decimal table converts: c * 1000, rounded, lies below 2^32. A FixedPointRangeError
// naming --accum otherwise (one conversion past it is undefined in GLSL; a sum past it wraps and is judged).
void RequirePackedDecimalConverts(std::span<const glm::vec3> contributions);
// The same over the records that enter the table.
void RequirePackedDecimalConverts(std::span<const Record> records);

}  // namespace hpsf

#endif  // HPSF_CORE_ACCUMULATION_H
