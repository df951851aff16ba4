// The sRGB transfer function hpsf's previews, heatmaps and SSIM share: linear light clamped to [0, 1] (a value
// that is not finite to 0), encoded as IEC 61966-2-1 specifies.
#ifndef HPSF_VERIFIER_METRICS_SRGB_H
#define HPSF_VERIFIER_METRICS_SRGB_H

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace hpsf {

inline float EncodeSrgb(float linear) {
  const float c = std::isfinite(linear) ? std::clamp(linear, 0.0f, 1.0f) : 0.0f;
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

inline std::uint8_t EncodeSrgb8(float linear) {
  return static_cast<std::uint8_t>(std::lround(EncodeSrgb(linear) * 255.0f));
}

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_SRGB_H
