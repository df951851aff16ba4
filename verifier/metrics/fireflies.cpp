#include "verifier/metrics/fireflies.h"

#include <cmath>
#include <stdexcept>

namespace hpsf {

std::uint64_t CountFireflies(const Image& image, std::uint32_t spp, const Image& reference,
                             const Image& reference_variance, std::uint32_t reference_spp, double sigmas) {
  if (image.width != reference.width || image.height != reference.height || reference_variance.width != image.width ||
      reference_variance.height != image.height) {
    throw std::invalid_argument("fireflies: the image, the converged image and its variance differ in size");
  }
  if (spp == 0 || reference_spp == 0) throw std::invalid_argument("fireflies: zero samples per pixel");
  std::uint64_t fireflies = 0;
  for (std::size_t p = 0; p < image.pixels.size(); ++p) {
    bool firefly = false;
    for (int c = 0; c < 3; ++c) {
      // The variance of path tracing's pixel mean at spp samples.
      const double variance = double(reference_variance.pixels[p][c]) * double(reference_spp) / double(spp);
      if (!(variance > 0.0)) continue;
      const double error = double(image.pixels[p][c]) - double(reference.pixels[p][c]);
      firefly |= !(std::abs(error) <= sigmas * std::sqrt(variance));  // a non-finite pixel counts
    }
    fireflies += firefly;
  }
  return fireflies;
}

}  // namespace hpsf
