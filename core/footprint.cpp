#include "core/footprint.h"

#include <cmath>

namespace hpsf {

float FootprintScale(double filter_width_px, double fov_y_radians, std::uint32_t image_height) {
  return static_cast<float>(filter_width_px * 2.0 * std::tan(fov_y_radians / 2.0) / double(image_height));
}

}  // namespace hpsf
