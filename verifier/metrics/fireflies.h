// The firefly count: the pixels of an image at s samples per pixel further from the converged image than k standard
// deviations of path tracing at s spp, in some colour channel. A pixel's per-sample variance is the converged image's
// variance of the mean times its samples (hpsf reference's, tools/hpsf/converged_reference.h), so the yardstick is the
// same for every method: a filter's bright single-pixel dot (a cell of one record, Binder et al. §3.3) and path
// tracing's own firefly both count. k = 5: were a pixel's error normal, it would pass 5 sigma with probability
// 5.7e-7 (two-sided), 0.03 of a 256x256 image's three channels, so what is counted is the heavy tail, not the noise.
// A pixel whose converged variance is 0 in a channel (no sample varies there) is not judged in that channel: its
// error is a bias, which relMSE measures.
#ifndef HPSF_VERIFIER_METRICS_FIREFLIES_H
#define HPSF_VERIFIER_METRICS_FIREFLIES_H

#include <cstdint>

#include "core/image.h"

namespace hpsf {

inline constexpr double kFireflySigmas = 5.0;

// reference_variance: of each converged pixel's mean at reference_spp samples. Throws std::invalid_argument for
// images of other sizes or a zero spp.
std::uint64_t CountFireflies(const Image& image, std::uint32_t spp, const Image& reference,
                             const Image& reference_variance, std::uint32_t reference_spp,
                             double sigmas = kFireflySigmas);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_FIREFLIES_H
