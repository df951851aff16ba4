#include "tools/hpsf/pareto_plot.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "tools/hpsf/plot_canvas.h"

namespace hpsf {
namespace {

constexpr int kWidth = 960, kHeight = 600;
constexpr int kLeft = 90, kRight = 220, kTop = 44, kBottom = 64;  // the margins around the plot area

}  // namespace

Rgb8Image RenderParetoPlot(const std::string& title, const std::vector<TimedError>& points,
                           const std::vector<bool>& frontier) {
  using namespace plot;
  double min_time = INFINITY, max_time = 0.0, min_error = INFINITY, max_error = 0.0;
  for (const TimedError& p : points) {
    if (!(p.seconds > 0.0) || !(p.error > 0.0) || !std::isfinite(p.seconds) || !std::isfinite(p.error)) continue;
    min_time = std::min(min_time, p.seconds);
    max_time = std::max(max_time, p.seconds);
    min_error = std::min(min_error, p.error);
    max_error = std::max(max_error, p.error);
  }
  if (!(max_time > 0.0)) throw InputError("the Pareto plot: no point with a positive time and error");
  const LogAxis x = AxisOver(min_time, max_time, kLeft, kWidth - kRight);
  const LogAxis y = AxisOver(min_error, max_error, kHeight - kBottom, kTop);

  Canvas canvas(kWidth, kHeight, "the Pareto plot");
  canvas.DecadeGrid(x, y, kLeft, kWidth - kRight, kTop, kHeight - kBottom);
  canvas.Text((kLeft + kWidth - kRight) / 2, kHeight - 18, "seconds per frame (trace + filter)", 14, kText,
              OIIO::ImageBufAlgo::TextAlignX::Center);
  canvas.Text(12, kTop - 14, "relMSE", 14, kText);
  canvas.Text(kLeft, 26, title, 16, kText);

  // Methods in order of first appearance, each in its colour; frontier lines first, points over them.
  std::vector<std::string> methods;
  for (const TimedError& p : points) {
    if (std::find(methods.begin(), methods.end(), p.method) == methods.end()) methods.push_back(p.method);
  }
  std::vector<std::pair<std::string, Colour>> legend;
  // A method's colour by its name without the frames ("hpsf/emulated, 16 frames": "hpsf/emulated"), its frontiers
  // after more frames in darker shades of it.
  const auto base = [](const std::string& method) { return method.substr(0, method.find(", ")); };
  std::vector<std::string> bases;
  for (const std::string& method : methods) {
    if (std::find(bases.begin(), bases.end(), base(method)) == bases.end()) bases.push_back(base(method));
  }
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const std::size_t b = std::size_t(std::find(bases.begin(), bases.end(), base(methods[m])) - bases.begin());
    std::size_t before = 0, of_base = 0;
    for (std::size_t k = 0; k < methods.size(); ++k) {
      of_base += base(methods[k]) == bases[b];
      before += k < m && base(methods[k]) == bases[b];
    }
    const Colour colour = Shaded(MethodColour(bases[b], b), before, of_base);
    std::vector<std::size_t> line;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (frontier[i] && points[i].method == methods[m] && points[i].seconds > 0.0 && points[i].error > 0.0) {
        line.push_back(i);
      }
    }
    std::sort(line.begin(), line.end(),
              [&](std::size_t a, std::size_t b) { return points[a].seconds < points[b].seconds; });
    for (std::size_t k = 1; k < line.size(); ++k) {
      const TimedError &a = points[line[k - 1]], &b = points[line[k]];
      canvas.Line(x.At(a.seconds), y.At(a.error), x.At(b.seconds), y.At(b.error), colour);
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      const TimedError& p = points[i];
      if (p.method != methods[m] || !(p.seconds > 0.0) || !(p.error > 0.0)) continue;
      const int px = x.At(p.seconds), py = y.At(p.error), r = frontier[i] ? 4 : 2;
      canvas.Box(px - r, py - r, px + r, py + r, colour, true);
    }
    legend.emplace_back(methods[m], colour);
  }
  const int below = canvas.Legend(kWidth - kRight + 20, kTop + 10, kHeight - kBottom - 22, 22, 14, legend);
  canvas.Text(kWidth - kRight + 20, below + 10, "large: on the frontier", 12, kMuted);
  return canvas.Pixels();
}

}  // namespace hpsf
