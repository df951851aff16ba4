// An RGB float image, row-major from the top-left pixel, as the filters produce it.
#ifndef HPSF_CORE_IMAGE_H
#define HPSF_CORE_IMAGE_H

#include <cstdint>
#include <cstring>
#include <vector>

#include <glm/vec3.hpp>

namespace hpsf {

struct Image {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<glm::vec3> pixels;

  Image() = default;
  Image(std::uint32_t w, std::uint32_t h) : width(w), height(h), pixels(std::size_t(w) * h, glm::vec3(0.0f)) {}
  glm::vec3& At(std::uint32_t x, std::uint32_t y) { return pixels[std::size_t(y) * width + x]; }
  const glm::vec3& At(std::uint32_t x, std::uint32_t y) const { return pixels[std::size_t(y) * width + x]; }
};

// Bitwise equality: -0.0 and +0.0 differ, a NaN equals itself. No memcmp on an empty image's null data.
inline bool SameBits(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         (a.pixels.empty() || std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec3)) == 0);
}

}  // namespace hpsf

#endif  // HPSF_CORE_IMAGE_H
