// The tangent frame of a normal by Duff et al. 2017 ("Building an Orthonormal Basis, Revisited"), computed on
// the host in double precision and stored in the record, so the key path needs no division. The sign comes from
// the sign bit of n.z: -0.0 and +0.0 give different, equally valid frames.
#ifndef HPSF_CORE_TANGENT_FRAME_H
#define HPSF_CORE_TANGENT_FRAME_H

#include <string>

#include <glm/vec3.hpp>

namespace hpsf {

struct TangentFrame {
  glm::vec3 tangent;
  glm::vec3 bitangent;
  std::string ToString() const;
};

TangentFrame DuffTangentFrame(glm::vec3 normal);

}  // namespace hpsf

#endif  // HPSF_CORE_TANGENT_FRAME_H
