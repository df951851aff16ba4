// The second plot of `hpsf sweep`: relMSE's bias squared and variance (verifier/metrics/error_split.h)
// against filter width, both on log scales, one series per configuration the sweep varied only in its filter width.
// A wider cell averages more samples (less variance) over a larger region (more bias); where the two cross is the
// width that balances them. bias^2 is a line with filled points, the variance a line in the same colour with hollow
// points; a bias^2 estimate at or below 0 (the seeds' noise exceeding it) leaves a gap in its line.
#ifndef HPSF_TOOLS_HPSF_BIAS_VARIANCE_PLOT_H
#define HPSF_TOOLS_HPSF_BIAS_VARIANCE_PLOT_H

#include <string>
#include <vector>

#include "tools/hpsf/heatmap.h"

namespace hpsf {

struct WidthSeries {
  std::string label;  // the configuration without its filter width, e.g. "method=hpsf backend=emulated spp=4"
  std::string method;
  std::vector<double> widths, bias2, variance;  // in increasing width
};

// At least one positive width with a positive bias^2 or variance; an InputError otherwise.
Rgb8Image RenderBiasVariancePlot(const std::string& title, const std::vector<WidthSeries>& series);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_BIAS_VARIANCE_PLOT_H
