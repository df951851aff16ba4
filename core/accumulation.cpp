#include "core/accumulation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "core/format.h"
#include "core/input_check.h"
#include "core/shared/float_bits.h"
#include "core/shared/packed_sums.h"

namespace hpsf {

Accumulation ParseAccumulation(const std::string& text) {
  if (text == "fixed64") return Accumulation::kFixed64;
  if (text == "float32") return Accumulation::kFloat32;
  if (text == "packed-decimal") return Accumulation::kPackedDecimal;
  throw ConfigError("--accum", "expected fixed64, float32 or packed-decimal; got '" + text + "'");
}

std::string ToString(Accumulation accumulation) {
  switch (accumulation) {
    case Accumulation::kFixed64:
      return "fixed64";
    case Accumulation::kFloat32:
      return "float32";
    case Accumulation::kPackedDecimal:
      return "packed-decimal";
  }
  return "?";
}

float SumScale(Accumulation accumulation, int fixed_point_bits) {
  if (accumulation == Accumulation::kPackedDecimal) return shared::kPackedDecimalScale;
  return shared::PowerOfTwo(fixed_point_bits);
}

double IntegerSumValue(std::uint64_t sum, Accumulation accumulation, int fixed_point_bits) {
  if (accumulation == Accumulation::kPackedDecimal) return double(sum) / double(shared::kPackedDecimalScale);
  return FromFixedPoint(sum, fixed_point_bits);
}

void RequirePackedDecimalConverts(std::span<const glm::vec3> contributions) {
  float largest = 0.0f;
  for (const glm::vec3& c : contributions) largest = std::max({largest, c.x, c.y, c.z});
  // The product rounds to float as on the device; compared before the conversion, which past 2^32 is undefined.
  if (std::nearbyint(largest * shared::kPackedDecimalScale) < 0x1p32f) return;
  throw FixedPointRangeError(
      "--accum", "packed-decimal holds a record's channel times 1000 in 32 bits; a contribution of " +
                     FormatFloat(largest) + " in this batch does not fit (4294967.295 at most): use fixed64");
}

void RequirePackedDecimalConverts(std::span<const Record> records) {
  std::vector<glm::vec3> contributions;
  for (const Record& r : records) {
    if (shared::RecordHasVertex(r) && CheckRecordInputs(r) == InputVerdict::kAccepted)
      contributions.push_back(glm::vec3(r.contribution));
  }
  RequirePackedDecimalConverts(contributions);
}

}  // namespace hpsf
