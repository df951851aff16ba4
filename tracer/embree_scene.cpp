#include "tracer/embree_scene.h"

#include <limits>
#include <stdexcept>
#include <string>

namespace hpsf {
namespace {

RTCRay MakeRay(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) {
  RTCRay ray{};
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = direction.x;
  ray.dir_y = direction.y;
  ray.dir_z = direction.z;
  ray.tnear = t_near;
  ray.tfar = t_far;
  ray.mask = 0xFFFFFFFFu;
  return ray;
}

}  // namespace

EmbreeScene::EmbreeScene(const Scene& scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_)
    throw std::runtime_error("Embree: cannot create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) +
                             ")");
  scene_ = rtcNewScene(device_);
  // Robust traversal avoids missed hits on shared edges; high-quality builds are deterministic in Embree.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  const std::size_t n = scene.triangles.size();
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (std::size_t i = 0; i < n; ++i) {
    const Triangle& t = scene.triangles[i];
    const glm::vec3 corners[3] = {t.p0, t.p1, t.p2};
    for (int c = 0; c < 3; ++c) {
      for (int axis = 0; axis < 3; ++axis) vertices[9 * i + 3 * c + axis] = corners[c][axis];
      indices[3 * i + c] = static_cast<unsigned>(3 * i + c);
    }
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree: building the scene failed");
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

std::optional<Hit> EmbreeScene::Intersect(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit ray_hit{};
  ray_hit.ray = MakeRay(origin, direction, t_near, t_far);
  ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &ray_hit);
  if (ray_hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return Hit{ray_hit.hit.primID, ray_hit.ray.tfar, ray_hit.hit.u, ray_hit.hit.v};
}

bool EmbreeScene::Occluded(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = MakeRay(origin, direction, t_near, t_far);
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();
}

}  // namespace hpsf
