// What a filtered frame must be before `hpsf render` or `hpsf replay` writes or reports it: no fixed64 sum wrapped and
// no pixel that is not finite. Several filtered bounces feed each frame's table into the next, so the light can grow
// frame after frame past what the F of the first frame holds (a furnace of albedo 1 grows without bound), or in
// float32 towards Inf. Every backend counts its wraps (core/hashed_run.h, the reference's stats); hpsf refuses such
// a frame (exit 3, nothing written) instead of writing an image of wrapped sums: it neither re-scales a table
// mid-sequence, which would change the bits of every cell the frame did not touch, nor filters on.
#ifndef HPSF_TOOLS_HPSF_FRAME_SOUNDNESS_H
#define HPSF_TOOLS_HPSF_FRAME_SOUNDNESS_H

#include "core/backend.h"
#include "core/filter_config.h"
#include "core/image.h"

namespace hpsf {

// A FixedPointRangeError naming --fixed-point-bits (when given) or --accum, the frame and the count, when the
// backend's last frame wrapped a fixed64 sum; a ConfigError naming --accum when a pixel of `image` is not finite.
void RequireSoundFrame(const Backend& backend, const Image& image, const FilterConfig& config);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_FRAME_SOUNDNESS_H
