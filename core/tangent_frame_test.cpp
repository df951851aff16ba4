#include "core/tangent_frame.h"

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace hpsf {
namespace {

void ExpectOrthonormal(glm::vec3 n, bool n_is_unit) {
  const TangentFrame f = DuffTangentFrame(n);
  const glm::dvec3 t(f.tangent), b(f.bitangent), dn(n);
  EXPECT_NEAR(glm::length(t), 1.0, 1e-6) << f.ToString();
  EXPECT_NEAR(glm::length(b), 1.0, 1e-6) << f.ToString();
  EXPECT_NEAR(glm::dot(t, b), 0.0, 1e-6) << f.ToString();
  if (n_is_unit) {
    EXPECT_NEAR(glm::dot(t, dn), 0.0, 1e-6) << f.ToString();
    EXPECT_NEAR(glm::dot(b, dn), 0.0, 1e-6) << f.ToString();
    EXPECT_NEAR(glm::length(glm::cross(t, b) - dn), 0.0, 1e-6) << f.ToString();  // right-handed
  }
}

TEST(TangentFrame, OrthonormalOnASphereOfNormals) {
  for (int i = 0; i <= 200; ++i) {
    for (int j = 0; j < 400; ++j) {
      const double theta = M_PI * i / 200.0, phi = 2.0 * M_PI * j / 400.0;
      const glm::vec3 n(glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
      ExpectOrthonormal(glm::normalize(n), true);
    }
  }
}

TEST(TangentFrame, OrthonormalAtAxesSignedZerosAndWithin1e7OfAnAxis) {
  std::vector<glm::vec3> normals;
  for (float sign : {1.0f, -1.0f}) {
    for (float zero : {0.0f, -0.0f}) {
      normals.push_back({sign, zero, zero});
      normals.push_back({zero, sign, zero});
      normals.push_back({zero, zero, sign});
      for (float e : {1e-7f, -1e-7f, 1e-30f}) {
        normals.push_back(glm::normalize(glm::vec3(e, zero, sign)));
        normals.push_back(glm::normalize(glm::vec3(zero, e, sign)));
        normals.push_back(glm::normalize(glm::vec3(e, e, sign)));
        normals.push_back(glm::normalize(glm::vec3(sign, e, zero)));
      }
    }
  }
  for (glm::vec3 n : normals) ExpectOrthonormal(n, true);
}

TEST(TangentFrame, ZeroNormalsStillGiveAnOrthonormalPairAndTheSignBitDecides) {
  ExpectOrthonormal(glm::vec3(0.0f, 0.0f, 0.0f), false);
  ExpectOrthonormal(glm::vec3(0.0f, 0.0f, -0.0f), false);
  const TangentFrame plus = DuffTangentFrame(glm::vec3(0.0f, 0.0f, 0.0f));
  const TangentFrame minus = DuffTangentFrame(glm::vec3(0.0f, 0.0f, -0.0f));
  EXPECT_EQ(plus.bitangent.y, 1.0f);
  EXPECT_EQ(minus.bitangent.y, -1.0f);
  // The same holds for unit normals on the equator: n.z = +0 and -0 pick the two branches.
  EXPECT_EQ(DuffTangentFrame(glm::vec3(1.0f, 0.0f, 0.0f)).tangent.z, -1.0f);
  EXPECT_EQ(DuffTangentFrame(glm::vec3(1.0f, 0.0f, -0.0f)).tangent.z, 1.0f);
}

}  // namespace
}  // namespace hpsf
