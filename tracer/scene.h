// A scene as the tracer sees it: a pinhole camera, diffuse materials (albedo, two-sided emission), triangles
// and an optional constant sky. Every shape of a scene file becomes triangles when it is loaded; a named shape
// keeps its triangles' range, so keyframes (animation.h) can move it.
#ifndef HPSF_TRACER_SCENE_H
#define HPSF_TRACER_SCENE_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "tracer/animation.h"

namespace hpsf {

// The L-infinity norm: the scale that float spacing and the scene's extent are measured in.
inline double MaxAbs(glm::dvec3 p) { return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}); }

struct Camera {
  glm::dvec3 position{0.0};
  glm::dvec3 look_at{0.0, 0.0, 1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_y_degrees = 40.0;
};

struct Material {
  std::string name;
  glm::vec3 albedo{0.0f};
  glm::vec3 emission{0.0f};  // radiance, emitted on both sides
  bool IsEmissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

struct Triangle {
  glm::vec3 p0, p1, p2;
  std::uint32_t material = 0;
};

struct NamedShape {
  std::string name;
  std::uint32_t first_triangle = 0;
  std::uint32_t triangle_count = 0;
};

struct Scene {
  std::string name;
  Camera camera;
  std::vector<Material> materials;
  std::vector<Triangle> triangles;
  glm::vec3 sky{0.0f};  // radiance of rays that leave the scene
  std::vector<NamedShape> shapes;
  Animation animation;  // names only shapes in `shapes`

  // The scene as it stands at `frame`: the camera and the animated shapes moved to their interpolated keys, an
  // animated emitter's radiance scaled (on a copy of its material). A static scene is returned as it is. An
  // InputError if the camera's position and look_at meet at that frame.
  Scene AtFrame(std::uint32_t frame) const;
  // Moves and scales everything, camera and keyframes included: world = (local * scale) + translate.
  void Transform(double scale, glm::dvec3 translate);
  // The largest |coordinate| of any vertex or of the camera: the scale of float spacing in the scene.
  double Extent() const;
};

}  // namespace hpsf

#endif  // HPSF_TRACER_SCENE_H
