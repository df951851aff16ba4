#include "tools/hpsf/bias_variance_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "tools/hpsf/plot_canvas.h"

namespace hpsf {
namespace {

constexpr int kPlotWidth = 960, kPlotHeight = 600;
constexpr int kMarginLeft = 90, kMarginRight = 330, kMarginTop = 44, kMarginBottom = 64;

bool Plotted(double width, double value) { return width > 0.0 && value > 0.0 && std::isfinite(value); }

// One series' values as a line through its plotted points, each point a box, filled or hollow.
void DrawValues(plot::Canvas& canvas, const plot::LogAxis& x, const plot::LogAxis& y, const WidthSeries& s,
                const std::vector<double>& values, const plot::Colour& colour, bool filled) {
  int last_x = -1, last_y = -1;
  for (std::size_t k = 0; k < s.widths.size(); ++k) {
    if (!Plotted(s.widths[k], values[k])) {
      last_x = -1;  // a gap: the estimate is not a positive number
      continue;
    }
    const int px = x.At(s.widths[k]), py = y.At(values[k]);
    if (last_x >= 0) canvas.Line(last_x, last_y, px, py, colour);
    canvas.Box(px - 4, py - 4, px + 4, py + 4, colour, filled);
    last_x = px;
    last_y = py;
  }
}

}  // namespace

Rgb8Image RenderBiasVariancePlot(const std::string& title, const std::vector<WidthSeries>& series) {
  using namespace plot;
  double min_width = INFINITY, max_width = 0.0, min_value = INFINITY, max_value = 0.0;
  for (const WidthSeries& s : series) {
    for (std::size_t k = 0; k < s.widths.size(); ++k) {
      for (double v : {s.bias2[k], s.variance[k]}) {
        if (!Plotted(s.widths[k], v)) continue;
        min_width = std::min(min_width, s.widths[k]);
        max_width = std::max(max_width, s.widths[k]);
        min_value = std::min(min_value, v);
        max_value = std::max(max_value, v);
      }
    }
  }
  if (!(max_width > 0.0)) throw InputError("the bias and variance plot: no positive bias^2 or variance");
  // The widths' own axis: log2 spacing, each swept width labelled.
  const double low = std::log10(min_width), high = max_width > min_width ? std::log10(max_width) : low + 1.0;
  const LogAxis x{low, high, kMarginLeft + 30, kPlotWidth - kMarginRight - 30};
  const LogAxis y = AxisOver(min_value, max_value, kPlotHeight - kMarginBottom, kMarginTop);

  Canvas canvas(kPlotWidth, kPlotHeight, "the bias and variance plot");
  for (int e = int(y.low); e <= int(y.high); ++e) {
    const int py = y.At(std::pow(10.0, e));
    canvas.Line(kMarginLeft, py, kPlotWidth - kMarginRight, py, kGrid);
    canvas.Text(kMarginLeft - 8, py + 5, Decade(e), 13, kMuted, OIIO::ImageBufAlgo::TextAlignX::Right);
  }
  std::vector<double> widths;
  for (const WidthSeries& s : series) widths.insert(widths.end(), s.widths.begin(), s.widths.end());
  std::sort(widths.begin(), widths.end());
  widths.erase(std::unique(widths.begin(), widths.end()), widths.end());
  for (double w : widths) {
    if (!(w > 0.0)) continue;
    const int px = x.At(w);
    canvas.Line(px, kMarginTop, px, kPlotHeight - kMarginBottom, kGrid);
    char label[32];
    std::snprintf(label, sizeof label, "%g", w);
    canvas.Text(px, kPlotHeight - kMarginBottom + 20, label, 13, kMuted, OIIO::ImageBufAlgo::TextAlignX::Center);
  }
  canvas.Text((kMarginLeft + kPlotWidth - kMarginRight) / 2, kPlotHeight - 18, "filter width (pixels at a primary hit)",
              14, kText, OIIO::ImageBufAlgo::TextAlignX::Center);
  canvas.Text(12, 26, title + ": relMSE's bias^2 (filled) and variance (hollow)", 16, kText);

  std::vector<std::string> methods, labels;
  std::vector<std::pair<std::string, Colour>> legend;
  for (const WidthSeries& s : series) labels.push_back(s.label);
  for (std::size_t i = 0; i < series.size(); ++i) {
    const WidthSeries& s = series[i];
    const auto known = std::find(methods.begin(), methods.end(), s.method);
    const std::size_t m = known - methods.begin();
    if (known == methods.end()) methods.push_back(s.method);
    // Series of one method in its colour, darker for each further one.
    std::size_t before = 0;
    for (std::size_t j = 0; j < i; ++j) before += series[j].method == s.method;
    Colour colour = MethodColour(s.method, m);
    for (float& c : colour.rgb) c *= float(std::pow(0.8, double(before)));
    DrawValues(canvas, x, y, s, s.bias2, colour, true);
    DrawValues(canvas, x, y, s, s.variance, colour, false);
    legend.emplace_back(DistinguishingWords(s.label, labels, s.method), colour);
  }
  canvas.Legend(kPlotWidth - kMarginRight + 20, kMarginTop + 10, kPlotHeight - kMarginBottom, 20, 12, legend);
  return canvas.Pixels();
}

}  // namespace hpsf
