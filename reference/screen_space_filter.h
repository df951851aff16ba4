// The screen-space baseline (Meijer §4.1, screen-space path space filtering): every filter vertex averages the
// contributions of the filter vertices of the pixels in a window around its pixel (9x9 by default) that pass its
// similarity test, the same one the radius search applies (filter_vertices.h: within HPSF's cell edge at its level
// in world space, the same normal word). A cross-bilateral filter with a box kernel on world position and normal;
// its neighbourhood is bounded by the screen, so it misses what lies off screen or behind the next silhouette.
#ifndef HPSF_REFERENCE_SCREEN_SPACE_FILTER_H
#define HPSF_REFERENCE_SCREEN_SPACE_FILTER_H

#include "core/filter_config.h"
#include "core/record.h"
#include "reference/filter_vertices.h"

namespace hpsf {

// window_radius_px: the window is (2 w + 1) pixels square.
NeighbourFilterResult ScreenSpaceFilter(const RecordBatch& batch, const FilterConfig& config, double radius_scale = 1.0,
                                        int window_radius_px = 4);

}  // namespace hpsf

#endif  // HPSF_REFERENCE_SCREEN_SPACE_FILTER_H
