#include "tracer/scene.h"

#include <algorithm>
#include <cmath>

namespace hpsf {
namespace {

glm::vec3 Apply(glm::vec3 p, double scale, glm::dvec3 translate) { return glm::vec3(glm::dvec3(p) * scale + translate); }

double MaxAbs(glm::dvec3 p) { return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}); }

}  // namespace

void Scene::Transform(double scale, glm::dvec3 translate) {
  for (Triangle& t : triangles) {
    t.p0 = Apply(t.p0, scale, translate);
    t.p1 = Apply(t.p1, scale, translate);
    t.p2 = Apply(t.p2, scale, translate);
  }
  camera.position = camera.position * scale + translate;
  camera.look_at = camera.look_at * scale + translate;
}

double Scene::Extent() const {
  double extent = MaxAbs(camera.position);
  for (const Triangle& t : triangles) extent = std::max({extent, MaxAbs(t.p0), MaxAbs(t.p1), MaxAbs(t.p2)});
  return extent;
}

}  // namespace hpsf
