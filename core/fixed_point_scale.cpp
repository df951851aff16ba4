#include "core/fixed_point_scale.h"

#include <cmath>

#include "core/input_check.h"
#include "core/shared/fixed_point.h"

namespace hpsf {
namespace {

constexpr unsigned __int128 kLimit = static_cast<unsigned __int128>(1) << 63;
constexpr unsigned __int128 kSaturated = static_cast<unsigned __int128>(1) << 127;

bool EntersTable(const Record& r) {
  return shared::RecordHasVertex(r) && CheckRecordInputs(r) == InputVerdict::kAccepted;
}

}  // namespace

unsigned __int128 FixedPointCeilingSum(std::span<const Record> records, int channel, int fraction_bits) {
  unsigned __int128 sum = 0;
  for (const Record& r : records) {
    if (!EntersTable(r)) continue;
    // c * 2^F is exact in double for every float c and F in [-126, 126].
    const double ceiling = std::ceil(std::ldexp(static_cast<double>(r.contribution[channel]), fraction_bits));
    if (ceiling >= 0x1p126) return kSaturated;
    sum += static_cast<unsigned __int128>(ceiling);
    if (sum >= kSaturated) return kSaturated;
  }
  return sum;
}

int ChooseFixedPointBits(std::span<const Record> records) {
  auto fits = [&](int f) {
    for (int channel = 0; channel < 3; ++channel) {
      if (FixedPointCeilingSum(records, channel, f) >= kLimit) return false;
    }
    return true;
  };
  // The sums grow with F, so binary search for the last F that fits.
  int low = shared::kFixedPointBitsMin, high = shared::kFixedPointBitsMax;
  if (!fits(low)) return low;  // unreachable for finite floats: every c * 2^-126 is below 2^2
  while (low < high) {
    const int mid = low + (high - low + 1) / 2;
    if (fits(mid)) {
      low = mid;
    } else {
      high = mid - 1;
    }
  }
  return low;
}

double FromFixedPoint(std::uint64_t value, int fraction_bits) {
  return std::ldexp(static_cast<double>(value), -fraction_bits);
}

}  // namespace hpsf
