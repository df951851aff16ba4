#include "tools/hpsf/series_convergence.h"

#include <cmath>
#include <cstdio>

namespace hpsf {

double ImageMean(const Image& image) {
  if (image.pixels.empty()) return 0.0;
  double sum = 0.0;
  for (const glm::vec3& p : image.pixels) sum += (double(p.x) + double(p.y) + double(p.z)) / 3.0;
  return sum / double(image.pixels.size());
}

std::uint32_t SeriesConvergence::RisingFrames() const {
  std::uint32_t rising = 0;
  for (std::size_t k = means.size(); k >= 2 && means[k - 1] > means[k - 2]; --k) ++rising;
  return rising;
}

double SeriesConvergence::LastRelativeChange() const {
  if (means.size() < 2) return 0.0;
  const double last = means.back(), before = means[means.size() - 2];
  return last == 0.0 ? std::abs(last - before) : std::abs(last - before) / std::abs(last);
}

bool SeriesConvergence::Converged() const {
  return RisingFrames() < kRisingFrames && LastRelativeChange() <= kSettledChange;
}

nlohmann::json SeriesConvergence::ToJson() const {
  return {{"means", means},
          {"rising_frames", RisingFrames()},
          {"last_relative_change", LastRelativeChange()},
          {"converged", Converged()}};
}

std::string SeriesConvergence::Summary() const {
  if (Converged()) return "converged";
  char text[200];
  if (RisingFrames() >= kRisingFrames) {
    std::snprintf(text, sizeof text, "not converged: the image mean rose in each of the last %u frames, %.6g to %.6g",
                  RisingFrames(), means[means.size() - 1 - RisingFrames()], means.back());
  } else {
    std::snprintf(text, sizeof text, "not converged: the image mean changed by %.3g%% in the last frame",
                  100.0 * LastRelativeChange());
  }
  return text;
}

}  // namespace hpsf
