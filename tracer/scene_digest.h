// A 64-bit digest of what the tracer sees of a scene at one frame: the camera, every material, every triangle and
// the sky, as their bits (FNV-1a). Two scenes with the same digest trace the same records (with the same tracer
// and options), whatever file, mesh or built-in name they came from; a changed vertex, albedo or keyframe changes it.
#ifndef HPSF_TRACER_SCENE_DIGEST_H
#define HPSF_TRACER_SCENE_DIGEST_H

#include <cstdint>

#include "tracer/scene.h"

namespace hpsf {

// The digest of scene.AtFrame(frame).
std::uint64_t SceneDigest(const Scene& scene, std::uint32_t frame);

}  // namespace hpsf

#endif  // HPSF_TRACER_SCENE_DIGEST_H
