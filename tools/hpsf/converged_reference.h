// A converged image to measure error against (`hpsf reference`): plain path tracing at many samples
// per pixel, traced in passes of a few samples each, so that memory stays that of one pass, with each pixel's
// variance of the mean from the spread of the pass means. Pass p traces with its own seed, drawn from the counter
// RNG from (seed, frame, p), so the image is a pure function of the scene and the request: no bit depends on
// threads, and a request traced twice gives the same bits.
#ifndef HPSF_TOOLS_HPSF_CONVERGED_REFERENCE_H
#define HPSF_TOOLS_HPSF_CONVERGED_REFERENCE_H

#include <cstdint>
#include <functional>
#include <string>

#include "core/image.h"
#include "tracer/path_tracer.h"
#include "tracer/scene.h"

namespace hpsf {

struct ReferenceRequest {
  TraceOptions trace;  // size, seed, frame, depth, filter bounce; its samples_per_pixel is the pass's
  std::uint32_t samples_per_pixel = 256;
  std::uint32_t pass_samples = 16;  // samples per pixel of each pass; divides samples_per_pixel, at least 2 passes

  void Validate() const;  // ConfigError naming --spp or --pass-spp
  std::uint32_t Passes() const { return samples_per_pixel / pass_samples; }
  // Every figure the image depends on, with the scene's digest (its content, not its name or path) and the tracer
  // version, as one line: the cache key's text, and what a cached image is checked against.
  std::string Description(std::uint64_t scene_digest) const;
};

struct ConvergedImage {
  Image mean;      // the image at samples_per_pixel
  Image variance;  // of each pixel's mean, per channel: the pass means' sample variance over the passes
};

// progress(done, total) after each pass.
ConvergedImage RenderConverged(const Scene& scene, const ReferenceRequest& request,
                               const std::function<void(std::uint32_t, std::uint32_t)>& progress = {});

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_CONVERGED_REFERENCE_H
