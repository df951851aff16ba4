#include "core/fixed_point_scale.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_check.h"
#include "core/shared/fixed_point.h"
#include "core/shared/second_moment.h"

namespace hpsf {
namespace {

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

void RequireFixedPointConverts(std::span<const glm::vec3> contributions, int fixed_point_bits) {
  float largest = 0.0f;
  for (const glm::vec3& c : contributions) largest = std::max({largest, c.x, c.y, c.z});
  // c * 2^F is exact in double; below 2^64 its rounding to even stays below 2^64 too (the largest float under 2^64
  // is 2^64 - 2^40).
  if (std::ldexp(double(largest), fixed_point_bits) < 0x1p64) return;
  const int exponent = std::ilogb(largest);
  throw FixedPointRangeError("--fixed-point-bits",
                             "F " + std::to_string(fixed_point_bits) + " is too large for a contribution of " +
                                 std::to_string(largest) + " in this batch: it reaches 2^64, past fixed64's range; F " +
                                 std::to_string(63 - exponent) + " at most converts it");
}

void RequireFixedPointConverts(std::span<const Record> records, int fixed_point_bits) {
  std::vector<glm::vec3> contributions;
  for (const Record& r : records) {
    if (EntersTable(r)) contributions.push_back(glm::vec3(r.contribution));
  }
  RequireFixedPointConverts(contributions, fixed_point_bits);
}

int ChooseFixedPointBits(std::span<const Record> records, std::uint32_t frames) {
  std::vector<glm::vec3> contributions;
  contributions.reserve(records.size());
  for (const Record& r : records) {
    if (EntersTable(r)) contributions.push_back(glm::vec3(r.contribution));
  }
  return ChooseFixedPointBitsOf(contributions, {}, frames);
}

int ChooseFixedPointBitsOf(std::span<const glm::vec3> contributions, const RangeRunner& runner, std::uint32_t frames) {
  if (frames == 0) throw ConfigError("--frames", "must be at least 1");
  const std::uint64_t limit = (std::uint64_t(1) << 63) / frames;  // every channel's sum stays below it
  const RangeRunner run = runner ? runner : RangeRunner([](std::size_t n, const auto& work) { work(0, n); });
  std::mutex merge;
  glm::dvec3 total(0.0);  // only the starting estimate: its rounding order does not change the answer
  run(contributions.size(), [&](std::size_t begin, std::size_t end) {
    glm::dvec3 part(0.0);
    for (std::size_t i = begin; i < end; ++i) part += glm::dvec3(contributions[i]);
    const std::lock_guard lock(merge);
    total += part;
  });
  // Exact test of one F: every c * 2^F is exact in double; each ceiling below 2^63 fits a uint64. All three
  // channels in one pass per range, the running sums in registers; ranges add up in 128 bits.
  auto fits = [&](int f) {
    const double scale = std::ldexp(1.0, f);
    std::atomic<bool> overflow{false};
    unsigned __int128 x_total = 0, y_total = 0, z_total = 0;
    run(contributions.size(), [&](std::size_t begin, std::size_t end) {
      std::uint64_t x = 0, y = 0, z = 0;
      for (std::size_t i = begin; i < end; ++i) {
        const glm::vec3& c = contributions[i];
        const double cx = std::ceil(double(c.x) * scale), cy = std::ceil(double(c.y) * scale),
                     cz = std::ceil(double(c.z) * scale);
        if (cx >= 0x1p63 || cy >= 0x1p63 || cz >= 0x1p63) {
          overflow = true;
          return;
        }
        x += static_cast<std::uint64_t>(cx);  // both terms below 2^63: no wrap
        y += static_cast<std::uint64_t>(cy);
        z += static_cast<std::uint64_t>(cz);
        if (x >= limit || y >= limit || z >= limit) {
          overflow = true;
          return;
        }
      }
      const std::lock_guard lock(merge);
      x_total += x;
      y_total += y;
      z_total += z;
    });
    return !overflow && x_total < limit && y_total < limit && z_total < limit;
  };
  // Start from the estimate sum(ceil(c 2^F)) <= 2^F sum(c) + n, then step to the exact answer: usually one or
  // two passes instead of a binary search over all 253 values.
  const double largest = std::max({total.x, total.y, total.z});
  int f = shared::kFixedPointBitsMax;
  const double room = double(limit) - double(contributions.size()) - 1.0;
  if (largest > 0.0 && room <= 0.0) f = shared::kFixedPointBitsMin;  // many frames of many records: search upward
  if (largest > 0.0 && room > 0.0) {
    f = static_cast<int>(std::clamp(std::floor(std::log2(room / largest)), double(shared::kFixedPointBitsMin),
                                    double(shared::kFixedPointBitsMax)));
  }
  while (f > shared::kFixedPointBitsMin && !fits(f)) --f;
  while (f < shared::kFixedPointBitsMax && fits(f + 1)) ++f;
  return f;
}

int ChooseSquareBitsOf(std::span<const glm::vec3> contributions, const RangeRunner& runner, std::uint32_t frames) {
  if (frames == 0) throw ConfigError("--frames", "must be at least 1");
  const std::uint64_t limit = (std::uint64_t(1) << 63) / frames;
  const RangeRunner run = runner ? runner : RangeRunner([](std::size_t n, const auto& work) { work(0, n); });
  std::mutex merge;
  // Exact test of one G: y^2 * 2^G is exact in double (y^2 < 2^260, G >= -126 keeps it normal), and so its ceiling.
  auto fits = [&](int g) {
    const double scale = std::ldexp(1.0, g);
    std::atomic<bool> overflow{false};
    unsigned __int128 total = 0;
    run(contributions.size(), [&](std::size_t begin, std::size_t end) {
      std::uint64_t part = 0;
      for (std::size_t i = begin; i < end && !overflow; ++i) {
        const double y = shared::Brightness(contributions[i]);
        const double ceiling = std::ceil(y * y * scale);
        if (ceiling >= 0x1p63) {
          overflow = true;
          return;
        }
        part += static_cast<std::uint64_t>(ceiling);  // both terms below 2^63: no wrap
        if (part >= limit) {
          overflow = true;
          return;
        }
      }
      const std::lock_guard lock(merge);
      total += part;
    });
    return !overflow && total < limit;
  };
  // A binary search: fits is monotone in G (a larger scale never shrinks a ceiling).
  if (!fits(shared::kFixedPointBitsMin)) return shared::kFixedPointBitsMin;
  int low = shared::kFixedPointBitsMin, high = shared::kFixedPointBitsMax;
  while (low < high) {
    const int middle = low + (high - low + 1) / 2;
    if (fits(middle)) {
      low = middle;
    } else {
      high = middle - 1;
    }
  }
  return low;
}

int ChooseSquareBits(std::span<const Record> records, std::uint32_t frames) {
  std::vector<glm::vec3> contributions;
  for (const Record& r : records) {
    if (EntersTable(r)) contributions.push_back(glm::vec3(r.contribution));
  }
  return ChooseSquareBitsOf(contributions, {}, frames);
}

void RequireSquaresConvert(std::span<const glm::vec3> contributions, int square_bits) {
  double largest = 0.0;
  for (const glm::vec3& c : contributions) largest = std::max(largest, shared::Brightness(c));
  // y^2 * 2^G rounds below 2^64 when it lies below 2^64 - 2^11, the largest double under 2^64.
  if (std::ldexp(largest * largest, square_bits) < 0x1p64) return;
  throw FixedPointRangeError("--second-moments", "G " + std::to_string(square_bits) +
                                                     ", the square sums' scale the table keeps, is too large for a "
                                                     "brightness of " +
                                                     std::to_string(largest) +
                                                     " in this frame: its square reaches 2^64, past fixed64's range; "
                                                     "give more --frames, which leaves G more room");
}

void RequireSquaresConvert(std::span<const Record> records, int square_bits) {
  std::vector<glm::vec3> contributions;
  for (const Record& r : records) {
    if (EntersTable(r)) contributions.push_back(glm::vec3(r.contribution));
  }
  RequireSquaresConvert(contributions, square_bits);
}

void RequireFloat32SquaresRange(int square_bits) {
  if (square_bits >= kFloat32FixedPointBitsMin) return;
  throw ConfigError("--second-moments", "float32 cannot hold this batch's squares: their total is about 2^" +
                                            std::to_string(62 - square_bits) +
                                            " or more, so a cell's float32 sum of squares could overflow to Inf; use "
                                            "fixed64, or --second-moments off");
}

void RequireFloat32Range(int fixed_point_bits) {
  if (fixed_point_bits >= kFloat32FixedPointBitsMin) return;
  throw ConfigError("--accum", "float32 cannot hold this batch: a channel's contributions total about 2^" +
                                   std::to_string(62 - fixed_point_bits) +
                                   " or more (F = " + std::to_string(fixed_point_bits) +
                                   "), so a cell's float32 sum could overflow to Inf; use fixed64, or scale the batch"
                                   " below 2^127 per channel");
}

double FromFixedPoint(std::uint64_t value, int fraction_bits) {
  return std::ldexp(static_cast<double>(value), -fraction_bits);
}

}  // namespace hpsf
