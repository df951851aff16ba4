// The Pareto plot of `hpsf sweep` as a PNG: relMSE against time per frame (trace and filter), both on
// log scales, every configuration a point in its method's colour and each method's frontier (verifier/metrics/pareto.h)
// a line through its frontier points; plain path tracing's frontier is the line the filters must get under at equal
// time. Drawn with OpenImageIO's ImageBufAlgo, text in DejaVu Sans, for the documentation and the HTML report alike.
#ifndef HPSF_TOOLS_HPSF_PARETO_PLOT_H
#define HPSF_TOOLS_HPSF_PARETO_PLOT_H

#include <string>
#include <vector>

#include "tools/hpsf/heatmap.h"
#include "verifier/metrics/pareto.h"

namespace hpsf {

// frontier: ParetoFrontier(points). At least one point with positive time and error; an InputError otherwise.
Rgb8Image RenderParetoPlot(const std::string& title, const std::vector<TimedError>& points,
                           const std::vector<bool>& frontier);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_PARETO_PLOT_H
