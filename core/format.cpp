#include "core/format.h"

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstdio>

namespace hpsf {

std::string FormatFloat(float x) {
  char buffer[32];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

std::string FormatDouble(double x) {
  char buffer[32];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

std::string FormatHex(unsigned int bits) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "0x%08x", bits);
  return buffer;
}

std::string FormatFloatBits(float x) {
  return FormatFloat(x) + " (" + FormatHex(std::bit_cast<std::uint32_t>(x)) + ")";
}

std::string FormatVec3(glm::vec3 v) {
  // Appended in place: GCC 12 at -O3 reports a false -Wrestrict on "literal" + std::string&& (GCC bug 105651).
  std::string text = "(";
  text.append(FormatFloat(v.x)).append(", ").append(FormatFloat(v.y)).append(", ").append(FormatFloat(v.z)).append(")");
  return text;
}

}  // namespace hpsf
