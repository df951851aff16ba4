#include "tracer/scene.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace hpsf {
namespace {

glm::vec3 Apply(glm::vec3 p, double scale, glm::dvec3 translate) {
  return glm::vec3(glm::dvec3(p) * scale + translate);
}

}  // namespace

void Scene::Transform(double scale, glm::dvec3 translate) {
  for (Triangle& t : triangles) {
    t.p0 = Apply(t.p0, scale, translate);
    t.p1 = Apply(t.p1, scale, translate);
    t.p2 = Apply(t.p2, scale, translate);
  }
  camera.position = camera.position * scale + translate;
  camera.look_at = camera.look_at * scale + translate;
  for (CameraKey& k : animation.camera) {
    k.position = k.position * scale + translate;
    k.look_at = k.look_at * scale + translate;
  }
  for (ShapeAnimation& a : animation.shapes) {
    for (ShapeKey& k : a.keys) k.translate *= scale;
  }
}

Scene Scene::AtFrame(std::uint32_t frame) const {
  Scene s = *this;
  if (!animation.camera.empty()) {
    const CameraKey k = CameraAt(animation.camera, frame);
    s.camera.position = k.position;
    s.camera.look_at = k.look_at;
    if (k.position == k.look_at) {
      throw InputError(name + ": frame " + std::to_string(frame) + ": the camera's position and look_at meet");
    }
  }
  for (const ShapeAnimation& a : animation.shapes) {
    const auto shape =
        std::find_if(shapes.begin(), shapes.end(), [&](const NamedShape& n) { return n.name == a.shape; });
    if (shape == shapes.end()) throw InputError(name + ": keyframes for a shape not in the scene, '" + a.shape + "'");
    const ShapeKey k = ShapeAt(a.keys, frame);
    const auto begin = s.triangles.begin() + shape->first_triangle;
    const auto end = begin + shape->triangle_count;
    for (auto t = begin; t != end; ++t) {
      t->p0 = Apply(t->p0, 1.0, k.translate);
      t->p1 = Apply(t->p1, 1.0, k.translate);
      t->p2 = Apply(t->p2, 1.0, k.translate);
    }
    if (k.emission_scale != 1.0 && begin != end) {
      Material m = s.materials[begin->material];
      m.name += "@" + shape->name;
      m.emission = glm::vec3(glm::dvec3(m.emission) * k.emission_scale);
      s.materials.push_back(m);
      for (auto t = begin; t != end; ++t) t->material = std::uint32_t(s.materials.size() - 1);
    }
  }
  return s;
}

double Scene::Extent() const {
  double extent = MaxAbs(camera.position);
  for (const Triangle& t : triangles) extent = std::max({extent, MaxAbs(t.p0), MaxAbs(t.p1), MaxAbs(t.p2)});
  return extent;
}

}  // namespace hpsf
