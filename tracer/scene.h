// A scene as the tracer sees it: a pinhole camera, diffuse materials (albedo, two-sided emission), triangles
// and an optional constant sky. Every shape of a scene file becomes triangles when it is loaded.
#ifndef HPSF_TRACER_SCENE_H
#define HPSF_TRACER_SCENE_H

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace hpsf {

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

struct Scene {
  std::string name;
  Camera camera;
  std::vector<Material> materials;
  std::vector<Triangle> triangles;
  glm::vec3 sky{0.0f};  // radiance of rays that leave the scene

  // Moves and scales everything, camera included: world = (local * scale) + translate.
  void Transform(double scale, glm::dvec3 translate);
  // The largest |coordinate| of any vertex or of the camera: the scale of float spacing in the scene.
  double Extent() const;
};

}  // namespace hpsf

#endif  // HPSF_TRACER_SCENE_H
