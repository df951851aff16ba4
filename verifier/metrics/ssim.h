// SSIM (Wang et al. 2004) from OpenCV's quality module, not written here. SSIM's constants assume values in
// [0, 255], so it is taken on what a person sees: each colour channel sRGB-encoded from [0, 1] and scaled to
// 255, with OpenCV's 11x11 Gaussian window. 1 means identical; the mean over the colour channels is reported.
#ifndef HPSF_VERIFIER_METRICS_SSIM_H
#define HPSF_VERIFIER_METRICS_SSIM_H

#include "verifier/metrics/channel_image.h"

namespace hpsf {

// A is the test image, B the reference; they must be comparable (CheckComparable).
double SrgbSsim(const ChannelImage& a, const ChannelImage& b);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_SSIM_H
