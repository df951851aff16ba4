// The debug image of the cells' variance (--second-moments): per pixel, the variance of the cells its samples resolved
// from (verifier/metrics/cell_variance.h), on a log scale from its 1st to its 99th percentile through the heatmap's
// colour map; a pixel with no cell is black. `hpsf render` writes it beside its output as OUT.cell-variance.png.
#ifndef HPSF_TOOLS_HPSF_CELL_VARIANCE_MAP_H
#define HPSF_TOOLS_HPSF_CELL_VARIANCE_MAP_H

#include <span>
#include <string>

#include "tools/hpsf/heatmap.h"

namespace hpsf {

Rgb8Image RenderCellVarianceMap(std::span<const float> variance, int width, int height);

// OUT.exr's debug image's path: OUT.cell-variance.png.
std::string CellVarianceMapPath(const std::string& output);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_CELL_VARIANCE_MAP_H
