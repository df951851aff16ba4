#include "tracer/animation.h"

#include <algorithm>

namespace hpsf {
namespace {

// The index of the last key at or before `frame` and the weight of the next one; keys must not be empty.
template <typename Key>
std::pair<std::size_t, double> Bracket(const std::vector<Key>& keys, std::uint32_t frame) {
  const auto after =
      std::upper_bound(keys.begin(), keys.end(), frame, [](std::uint32_t f, const Key& k) { return f < k.frame; });
  if (after == keys.begin()) return {0, 0.0};
  const std::size_t i = std::size_t(after - keys.begin()) - 1;
  if (after == keys.end()) return {i, 0.0};
  return {i, double(frame - keys[i].frame) / double(after->frame - keys[i].frame)};
}

glm::dvec3 Mix(glm::dvec3 a, glm::dvec3 b, double t) { return t == 0.0 ? a : a + (b - a) * t; }
double Mix(double a, double b, double t) { return t == 0.0 ? a : a + (b - a) * t; }

}  // namespace

CameraKey CameraAt(const std::vector<CameraKey>& keys, std::uint32_t frame) {
  const auto [i, t] = Bracket(keys, frame);
  const CameraKey& a = keys[i];
  if (t == 0.0) return {frame, a.position, a.look_at};
  const CameraKey& b = keys[i + 1];
  return {frame, Mix(a.position, b.position, t), Mix(a.look_at, b.look_at, t)};
}

ShapeKey ShapeAt(const std::vector<ShapeKey>& keys, std::uint32_t frame) {
  const auto [i, t] = Bracket(keys, frame);
  const ShapeKey& a = keys[i];
  if (t == 0.0) return {frame, a.translate, a.emission_scale};
  const ShapeKey& b = keys[i + 1];
  return {frame, Mix(a.translate, b.translate, t), Mix(a.emission_scale, b.emission_scale, t)};
}

}  // namespace hpsf
