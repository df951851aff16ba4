// The firefly count (verifier/metrics/fireflies.h) on constructed images: the yardstick scales with the spp, a pixel
// past k sigma in any channel counts once, a channel without variance is not judged, a non-finite pixel counts.
#include "verifier/metrics/fireflies.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

namespace hpsf {
namespace {

Image Filled(glm::vec3 value) {
  Image image(4, 1);
  for (glm::vec3& p : image.pixels) p = value;
  return image;
}

TEST(Fireflies, APixelPastFiveSigmaOfPathTracingAtItsSppCounts) {
  // Variance of the mean 0.01 at 100 spp: per sample 1, so at 4 spp sigma 0.5 and the bound 2.5.
  const Image reference = Filled(glm::vec3(1.0f)), variance = Filled(glm::vec3(0.01f));
  Image image = reference;
  image.pixels[0].x = 1.0f + 2.4f;                       // inside
  image.pixels[1].y = 1.0f + 2.6f;                       // past it, one channel
  image.pixels[2] = glm::vec3(1.0f - 2.6f, 4.0f, 4.0f);  // past it below and above: one pixel
  EXPECT_EQ(CountFireflies(image, 4, reference, variance, 100), 2u);
  // At 1 spp sigma is 1: 2.6 is inside.
  EXPECT_EQ(CountFireflies(image, 1, reference, variance, 100), 0u);
  EXPECT_EQ(CountFireflies(image, 4, reference, variance, 100, 2.0), 3u);
}

TEST(Fireflies, AChannelWithoutVarianceIsNotJudgedAndANonFinitePixelCounts) {
  const Image reference = Filled(glm::vec3(1.0f));
  Image variance = Filled(glm::vec3(0.01f));
  variance.pixels[0] = glm::vec3(0.0f);
  Image image = reference;
  image.pixels[0].x = 100.0f;  // no variance there: a bias, not a firefly
  image.pixels[1].z = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(CountFireflies(image, 4, reference, variance, 100), 1u);
  EXPECT_THROW(CountFireflies(Image(2, 2), 4, reference, variance, 100), std::invalid_argument);
  EXPECT_THROW(CountFireflies(image, 0, reference, variance, 100), std::invalid_argument);
}

}  // namespace
}  // namespace hpsf
