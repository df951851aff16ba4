// Amortized several filtered bounces (Meijer §4.4, A-nHPSF): each camera sample keeps the vertex where its path left
// off, and the next frame traces one more segment from it, so a path grows one vertex per frame and every vertex is
// filtered (core/transport.h carries the light beyond it back from the table). The state lives between TraceRecords
// calls of a sequence; it is valid only for the frame after the one that wrote it, of the same scene at the same size:
// any change to what the tracer sees (geometry, materials, camera: its SceneDigest) drops it, since a moved camera's
// sample follows another path and a moved surface may hide the stored vertex. The tracer cannot tell a camera cut
// from a camera move, so both drop it.
#ifndef HPSF_TRACER_PATH_CONTINUATION_H
#define HPSF_TRACER_PATH_CONTINUATION_H

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace hpsf {

// Where a sample's path left off: a surface vertex, with what keying it and extending the path need.
struct ContinuationVertex {
  bool valid = false;
  std::uint32_t bounce = 0;    // its index along the path (0: the primary hit)
  std::uint32_t material = 0;  // the scene's material index
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0};    // unit, facing the ray that reached it
  glm::dvec3 previous{0.0};  // the vertex before it (the camera for a primary hit)
  double d_prefix = 0.0;     // the path's length up to `previous`, as the key's level of detail measures it
};

class PathContinuation {
 public:
  // Whether the state a frame left continues into `frame` of the scene with `digest`, traced with this seed at this
  // size: written by frame - 1 of the same scene. Else TraceRecords starts every sample afresh.
  bool ContinuesInto(std::uint32_t frame, std::uint64_t digest, std::uint32_t seed, std::size_t samples) const {
    if (!written_ || frame != frame_ + 1 || seed != seed_ || samples != vertices_.size()) return false;
    return digest == digest_ || survives_scene_changes;
  }
  // Makes the state the one `frame` of the scene with `digest` leaves, for `samples` camera samples.
  std::vector<ContinuationVertex>& Write(std::uint32_t frame, std::uint64_t digest, std::uint32_t seed,
                                         std::size_t samples) {
    frame_ = frame;
    digest_ = digest;
    seed_ = seed;
    written_ = true;
    vertices_.resize(samples);
    return vertices_;
  }
  const std::vector<ContinuationVertex>& vertices() const { return vertices_; }

  // Broken on purpose, for the tests (docs/design/defects.md, "Broken transport"): the state kept across a change
  // of the scene, so that a sample continues a path the new scene does not hold.
  bool survives_scene_changes = false;

 private:
  bool written_ = false;
  std::uint32_t frame_ = 0;
  std::uint64_t digest_ = 0;
  std::uint32_t seed_ = 0;
  std::vector<ContinuationVertex> vertices_;
};

}  // namespace hpsf

#endif  // HPSF_TRACER_PATH_CONTINUATION_H
