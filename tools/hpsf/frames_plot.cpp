#include "tools/hpsf/frames_plot.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "tools/hpsf/plot_canvas.h"

namespace hpsf {
namespace {

constexpr int kFramesPlotWidth = 960, kFramesPlotHeight = 600;
constexpr int kFramesLeft = 90, kFramesRight = 330, kFramesTop = 44, kFramesBottom = 64;

bool FramePlotted(double value) { return value > 0.0 && std::isfinite(value); }

}  // namespace

Rgb8Image RenderFramesPlot(const std::string& title, const std::vector<FrameSeries>& series) {
  using namespace plot;
  double min_error = INFINITY, max_error = 0.0;
  std::size_t frames = 0;
  for (const FrameSeries& s : series) {
    frames = std::max(frames, s.relmse.size());
    for (const double e : s.relmse) {
      if (!FramePlotted(e)) continue;
      min_error = std::min(min_error, e);
      max_error = std::max(max_error, e);
    }
  }
  if (!(max_error > 0.0)) throw InputError("the plot of relMSE against frames: no positive relMSE");
  const LogAxis x =
      AxisOver(1.0, double(std::max<std::size_t>(frames, 2)), kFramesLeft, kFramesPlotWidth - kFramesRight);
  const LogAxis y = AxisOver(min_error, max_error, kFramesPlotHeight - kFramesBottom, kFramesTop);

  Canvas canvas(kFramesPlotWidth, kFramesPlotHeight, "the plot of relMSE against frames");
  canvas.DecadeGrid(x, y, kFramesLeft, kFramesPlotWidth - kFramesRight, kFramesTop, kFramesPlotHeight - kFramesBottom);
  canvas.Text((kFramesLeft + kFramesPlotWidth - kFramesRight) / 2, kFramesPlotHeight - 18, "frames", 14, kText,
              OIIO::ImageBufAlgo::TextAlignX::Center);
  canvas.Text(12, kFramesTop - 14, "relMSE", 14, kText);
  canvas.Text(kFramesLeft, 26, title + ": relMSE after each frame", 16, kText);

  std::vector<std::string> methods, labels;
  std::vector<std::pair<std::string, Colour>> legend;
  for (const FrameSeries& s : series) labels.push_back(s.label);
  for (std::size_t i = 0; i < series.size(); ++i) {
    const FrameSeries& s = series[i];
    const auto known = std::find(methods.begin(), methods.end(), s.method);
    const std::size_t m = std::size_t(known - methods.begin());
    if (known == methods.end()) methods.push_back(s.method);
    std::size_t before = 0, of_method = 0;
    for (std::size_t j = 0; j < series.size(); ++j) {
      of_method += series[j].method == s.method;
      before += j < i && series[j].method == s.method;
    }
    const Colour colour = Shaded(MethodColour(s.method, m), before, of_method);
    int last_x = -1, last_y = -1;
    for (std::size_t f = 0; f < s.relmse.size(); ++f) {
      if (!FramePlotted(s.relmse[f])) {
        last_x = -1;
        continue;
      }
      const int px = x.At(double(f + 1)), py = y.At(s.relmse[f]);
      if (last_x >= 0) canvas.Line(last_x, last_y, px, py, colour);
      last_x = px;
      last_y = py;
    }
    if (last_x >= 0) canvas.Box(last_x - 3, last_y - 3, last_x + 3, last_y + 3, colour, true);
    legend.emplace_back(DistinguishingWords(s.label, labels, s.method), colour);
  }
  canvas.Legend(kFramesPlotWidth - kFramesRight + 20, kFramesTop + 10, kFramesPlotHeight - kFramesBottom, 20, 12,
                legend);
  return canvas.Pixels();
}

}  // namespace hpsf
