#include "tracer/scene_digest.h"

#include <cstring>
#include <type_traits>

namespace hpsf {
namespace {

class Fnv1a {
 public:
  template <typename T>
  void Add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    for (const unsigned char b : bytes) hash_ = (hash_ ^ b) * 0x100000001b3ull;
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

void AddVec(Fnv1a& h, const glm::vec3& v) {
  h.Add(v.x);
  h.Add(v.y);
  h.Add(v.z);
}

void AddVec(Fnv1a& h, const glm::dvec3& v) {
  h.Add(v.x);
  h.Add(v.y);
  h.Add(v.z);
}

}  // namespace

std::uint64_t SceneDigest(const Scene& scene, std::uint32_t frame) {
  const Scene at = scene.AtFrame(frame);
  Fnv1a h;
  AddVec(h, at.camera.position);
  AddVec(h, at.camera.look_at);
  AddVec(h, at.camera.up);
  h.Add(at.camera.fov_y_degrees);
  h.Add(std::uint64_t(at.materials.size()));
  for (const Material& m : at.materials) {
    AddVec(h, m.albedo);
    AddVec(h, m.emission);
  }
  h.Add(std::uint64_t(at.triangles.size()));
  for (const Triangle& t : at.triangles) {
    AddVec(h, t.p0);
    AddVec(h, t.p1);
    AddVec(h, t.p2);
    h.Add(t.material);
  }
  AddVec(h, at.sky);
  return h.value();
}

}  // namespace hpsf
