#include "core/octahedral.h"

#include <algorithm>
#include <cmath>

namespace hpsf {
namespace {

std::uint32_t Quantize16(double p) {  // p in [-1, 1]
  double cell = std::floor((p + 1.0) * 0.5 * 65536.0);
  return static_cast<std::uint32_t>(std::clamp(cell, 0.0, 65535.0));
}

}  // namespace

std::uint32_t PackOctahedral16(glm::vec3 normal) {
  const double l1 = std::abs(double(normal.x)) + std::abs(double(normal.y)) + std::abs(double(normal.z));
  if (!(l1 > 0.0)) return 0;
  double u = normal.x / l1, v = normal.y / l1;
  if (std::signbit(normal.z)) {
    const double folded_u = (1.0 - std::abs(v)) * (std::signbit(u) ? -1.0 : 1.0);
    const double folded_v = (1.0 - std::abs(u)) * (std::signbit(v) ? -1.0 : 1.0);
    u = folded_u;
    v = folded_v;
  }
  return Quantize16(u) | (Quantize16(v) << 16);
}

}  // namespace hpsf
