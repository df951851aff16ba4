// A scene's keyframes (Binder et al. §3.4: the table persists while the scene moves): the camera,
// and named shapes, a light among them, moved by a translation and, for an emitter, scaled in emission. Between
// two keyframes a value is interpolated linearly; before the first and after the last it holds. A scene without
// keyframes is static: every frame is frame 0.
#ifndef HPSF_TRACER_ANIMATION_H
#define HPSF_TRACER_ANIMATION_H

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace hpsf {

struct CameraKey {
  std::uint32_t frame = 0;
  glm::dvec3 position{0.0};
  glm::dvec3 look_at{0.0, 0.0, 1.0};
};

struct ShapeKey {
  std::uint32_t frame = 0;
  glm::dvec3 translate{0.0};    // added to the shape's loaded position
  double emission_scale = 1.0;  // an emitter's radiance times this; 1 for any other shape
};

struct ShapeAnimation {
  std::string shape;  // a shape's "name" in the scene file
  std::vector<ShapeKey> keys;
};

// Keys in strictly increasing frames (the scene file's parser checks it).
struct Animation {
  std::vector<CameraKey> camera;
  std::vector<ShapeAnimation> shapes;
  bool Static() const { return camera.empty() && shapes.empty(); }
};

// The linear interpolation between the keys around `frame`, held before the first and after the last: exact at
// a key, and computed in double from the two keys only, so a frame's value does not depend on the frames before.
CameraKey CameraAt(const std::vector<CameraKey>& keys, std::uint32_t frame);
ShapeKey ShapeAt(const std::vector<ShapeKey>& keys, std::uint32_t frame);

}  // namespace hpsf

#endif  // HPSF_TRACER_ANIMATION_H
