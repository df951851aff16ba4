// The third plot of `hpsf sweep`, OUT/frames.png: relMSE against the frame, both on log scales, one line per
// configuration of more than one frame (its relMSE after each frame, averaged over the seeds); the legend names what
// tells the lines apart, and counts those it has no room for. Where the methods
// of several filtered bounces gain a bounce per frame and plain HPSF or path tracing only average, the lines part.
#ifndef HPSF_TOOLS_HPSF_FRAMES_PLOT_H
#define HPSF_TOOLS_HPSF_FRAMES_PLOT_H

#include <string>
#include <vector>

#include "tools/hpsf/heatmap.h"

namespace hpsf {

struct FrameSeries {
  std::string label;  // the configuration without its frames, e.g. "method=nhpsf backend=reference spp=1"
  std::string method;
  std::vector<double> relmse;  // after frame 1, 2, ...
};

// At least one positive relMSE; an InputError otherwise.
Rgb8Image RenderFramesPlot(const std::string& title, const std::vector<FrameSeries>& series);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_FRAMES_PLOT_H
