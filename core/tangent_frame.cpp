#include "core/tangent_frame.h"

#include <cmath>

#include "core/format.h"

namespace hpsf {

TangentFrame DuffTangentFrame(glm::vec3 normal) {
  const double x = normal.x, y = normal.y, z = normal.z;
  const double sign = std::signbit(normal.z) ? -1.0 : 1.0;
  const double a = -1.0 / (sign + z);
  const double b = x * y * a;
  TangentFrame frame;
  frame.tangent = glm::vec3(glm::dvec3(1.0 + sign * x * x * a, sign * b, -sign * x));
  frame.bitangent = glm::vec3(glm::dvec3(b, sign + y * y * a, -y));
  return frame;
}

std::string TangentFrame::ToString() const {
  return "[ TangentFrame tangent: " + FormatVec3(tangent) + " bitangent: " + FormatVec3(bitangent) + " ]";
}

}  // namespace hpsf
