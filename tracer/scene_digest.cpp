#include "tracer/scene_digest.h"

#include <type_traits>

#include "core/fnv1a.h"

namespace hpsf {
namespace {

// FNV-1a over a value's bytes, as they are (floats bit for bit).
class Digest {
 public:
  template <typename T>
  void Add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    hash_ = Fnv1a(&value, sizeof(T), hash_);
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = kFnv1aOffset;
};

void AddVec(Digest& h, const glm::vec3& v) {
  h.Add(v.x);
  h.Add(v.y);
  h.Add(v.z);
}

void AddVec(Digest& h, const glm::dvec3& v) {
  h.Add(v.x);
  h.Add(v.y);
  h.Add(v.z);
}

}  // namespace

std::uint64_t SceneDigest(const Scene& scene, std::uint32_t frame) {
  const Scene at = scene.AtFrame(frame);
  Digest h;
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
