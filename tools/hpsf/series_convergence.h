// Whether a sequence's image has settled (`hpsf render --frames N --transport on`). The transport adds a bounce per
// frame, so the image mean rises towards its limit: geometrically where every albedo is below 1, and for ever where
// one is not (a furnace of albedo 1). The judgement rejects "still rising": a series whose image mean rose in each of
// its last kRisingFrames frames, or changed by more than kSettledChange in its last, has not converged. For frames
// whose means were independent and identically distributed (settled, noise only) a run of 8 rises, 9 means in
// increasing order, has probability 1/9! = 2.8e-6; the temporal blend correlates neighbouring frames, which makes such
// a run likelier, so the rate at a given blend is measured, not assumed (docs/design/algorithm.md).
#ifndef HPSF_TOOLS_HPSF_SERIES_CONVERGENCE_H
#define HPSF_TOOLS_HPSF_SERIES_CONVERGENCE_H

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"

namespace hpsf {

inline constexpr std::uint32_t kRisingFrames = 8;
inline constexpr double kSettledChange = 0.01;  // relative

// The mean of an image's pixels over its three channels.
double ImageMean(const Image& image);

struct SeriesConvergence {
  std::vector<double> means;  // the image mean after each frame

  std::uint32_t RisingFrames() const;  // how many of the last frames each rose above the one before
  double LastRelativeChange() const;   // |m[k] - m[k-1]| / |m[k]| of the last frame; 0 with fewer than two
  bool Converged() const;
  // {"means", "rising_frames", "last_relative_change", "converged"}
  nlohmann::json ToJson() const;
  // "converged" or "not converged: ..." with the figures that decided it.
  std::string Summary() const;
};

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_SERIES_CONVERGENCE_H
