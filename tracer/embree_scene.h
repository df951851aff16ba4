// The scene's triangles in an Embree 3 BVH: closest-hit and occlusion queries for one ray at a time. Hits
// report the primitive and distance; the tracer computes positions and normals itself, in double, from the
// triangle, so they do not depend on Embree's internal arithmetic.
#ifndef HPSF_TRACER_EMBREE_SCENE_H
#define HPSF_TRACER_EMBREE_SCENE_H

#include <cstdint>
#include <optional>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "tracer/scene.h"

namespace hpsf {

struct Hit {
  std::uint32_t triangle;
  float t;
  float u, v;  // barycentric coordinates of p1 and p2
};

class EmbreeScene {
 public:
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  std::optional<Hit> Intersect(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const;
  bool Occluded(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const;

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace hpsf

#endif  // HPSF_TRACER_EMBREE_SCENE_H
