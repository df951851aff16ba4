#include "tools/hpsf/pareto_plot.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

#include "core/error.h"

namespace hpsf {
namespace {

constexpr const char* kPlotFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr int kWidth = 960, kHeight = 600;
constexpr int kLeft = 90, kRight = 220, kTop = 44, kBottom = 64;  // the margins around the plot area

struct Colour {
  float rgb[3];
};

// Distinct on the dark page the HTML report uses; plain path tracing light grey, the line to beat.
Colour MethodColour(const std::string& method, std::size_t index) {
  if (method == "pt") return {{0.85f, 0.85f, 0.85f}};
  static const Colour palette[] = {{{0.97f, 0.55f, 0.16f}}, {{0.35f, 0.70f, 0.95f}}, {{0.45f, 0.85f, 0.40f}},
                                   {{0.90f, 0.40f, 0.75f}}, {{0.95f, 0.85f, 0.30f}}, {{0.60f, 0.50f, 0.95f}}};
  return palette[index % (sizeof palette / sizeof palette[0])];
}

struct LogAxis {
  double low = 0.0, high = 1.0;  // decades, floor and ceiling of the data's log10
  int from = 0, to = 1;          // pixels
  int At(double value) const { return from + int(std::lround((std::log10(value) - low) / (high - low) * (to - from))); }
};

LogAxis AxisOver(double smallest, double largest, int from, int to) {
  LogAxis axis{std::floor(std::log10(smallest)), std::ceil(std::log10(largest)), from, to};
  if (axis.high <= axis.low) axis.high = axis.low + 1.0;
  return axis;
}

void Check(bool ok, const OIIO::ImageBuf& canvas) {
  if (!ok) throw InputError("the Pareto plot: " + canvas.geterror());
}

void Text(OIIO::ImageBuf& canvas, int x, int y, const std::string& text, int size, const float* colour,
          OIIO::ImageBufAlgo::TextAlignX align = OIIO::ImageBufAlgo::TextAlignX::Left) {
  Check(OIIO::ImageBufAlgo::render_text(canvas, x, y, text, size, kPlotFont, {colour, 3}, align), canvas);
}

std::string Decade(int exponent) {
  char text[16];
  std::snprintf(text, sizeof text, "1e%d", exponent);
  return text;
}

}  // namespace

Rgb8Image RenderParetoPlot(const std::string& title, const std::vector<TimedError>& points,
                           const std::vector<bool>& frontier) {
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

  OIIO::ImageBuf canvas(OIIO::ImageSpec(kWidth, kHeight, 3, OIIO::TypeDesc::FLOAT));
  const float background[3] = {0.106f, 0.11f, 0.118f}, grid[3] = {0.23f, 0.24f, 0.26f}, text[3] = {0.85f, 0.86f, 0.87f},
              muted[3] = {0.6f, 0.62f, 0.65f};
  Check(OIIO::ImageBufAlgo::fill(canvas, {background, 3}), canvas);
  for (int e = int(x.low); e <= int(x.high); ++e) {
    const int px = x.At(std::pow(10.0, e));
    Check(OIIO::ImageBufAlgo::render_line(canvas, px, kTop, px, kHeight - kBottom, {grid, 3}), canvas);
    Text(canvas, px, kHeight - kBottom + 20, Decade(e), 13, muted, OIIO::ImageBufAlgo::TextAlignX::Center);
  }
  for (int e = int(y.low); e <= int(y.high); ++e) {
    const int py = y.At(std::pow(10.0, e));
    Check(OIIO::ImageBufAlgo::render_line(canvas, kLeft, py, kWidth - kRight, py, {grid, 3}), canvas);
    Text(canvas, kLeft - 8, py + 5, Decade(e), 13, muted, OIIO::ImageBufAlgo::TextAlignX::Right);
  }
  Text(canvas, (kLeft + kWidth - kRight) / 2, kHeight - 18, "seconds per frame (trace + filter)", 14, text,
       OIIO::ImageBufAlgo::TextAlignX::Center);
  Text(canvas, 12, kTop - 14, "relMSE", 14, text);
  Text(canvas, kLeft, 26, title, 16, text);

  // Methods in order of first appearance, each in its colour; frontier lines first, points over them.
  std::vector<std::string> methods;
  for (const TimedError& p : points) {
    if (std::find(methods.begin(), methods.end(), p.method) == methods.end()) methods.push_back(p.method);
  }
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const Colour colour = MethodColour(methods[m], m);
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
      Check(OIIO::ImageBufAlgo::render_line(canvas, x.At(a.seconds), y.At(a.error), x.At(b.seconds), y.At(b.error),
                                            {colour.rgb, 3}),
            canvas);
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      const TimedError& p = points[i];
      if (p.method != methods[m] || !(p.seconds > 0.0) || !(p.error > 0.0)) continue;
      const int px = x.At(p.seconds), py = y.At(p.error), r = frontier[i] ? 4 : 2;
      Check(OIIO::ImageBufAlgo::render_box(canvas, px - r, py - r, px + r, py + r, {colour.rgb, 3}, true), canvas);
    }
    const int ly = kTop + 10 + int(m) * 22;
    Check(OIIO::ImageBufAlgo::render_box(canvas, kWidth - kRight + 20, ly - 4, kWidth - kRight + 28, ly + 4,
                                         {colour.rgb, 3}, true),
          canvas);
    Text(canvas, kWidth - kRight + 36, ly + 5, methods[m], 14, text);
  }
  Text(canvas, kWidth - kRight + 20, kTop + 20 + int(methods.size()) * 22, "large: on the frontier", 12, muted);

  Rgb8Image out;
  out.width = kWidth;
  out.height = kHeight;
  out.bytes.resize(std::size_t(kWidth) * kHeight * 3);
  Check(canvas.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, out.bytes.data()), canvas);
  return out;
}

}  // namespace hpsf
