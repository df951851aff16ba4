// The factor from path length to cell size: one cell spans filter_width_px pixels at the path length of a
// primary hit. Computed on the host, since it needs tan.
#ifndef HPSF_CORE_FOOTPRINT_H
#define HPSF_CORE_FOOTPRINT_H

#include <cstdint>

namespace hpsf {

// filter_width_px * 2 tan(fov_y / 2) / image_height, in double, rounded once to float.
float FootprintScale(double filter_width_px, double fov_y_radians, std::uint32_t image_height);

}  // namespace hpsf

#endif  // HPSF_CORE_FOOTPRINT_H
