#include "tools/hpsf/plot_canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "core/error.h"

namespace hpsf::plot {
namespace {

constexpr const char* kPlotFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

}  // namespace

Colour MethodColour(const std::string& method, std::size_t index) {
  if (method == "pt") return {{0.85f, 0.85f, 0.85f}};
  static const Colour palette[] = {{{0.97f, 0.55f, 0.16f}}, {{0.35f, 0.70f, 0.95f}}, {{0.45f, 0.85f, 0.40f}},
                                   {{0.90f, 0.40f, 0.75f}}, {{0.95f, 0.85f, 0.30f}}, {{0.60f, 0.50f, 0.95f}}};
  return palette[index % (sizeof palette / sizeof palette[0])];
}

Colour Shaded(Colour colour, std::size_t index, std::size_t count) {
  const double shade = count > 1 ? 1.0 - 0.55 * double(index) / double(count - 1) : 1.0;
  for (float& c : colour.rgb) c *= float(shade);
  return colour;
}

int LogAxis::At(double value) const {
  return from + int(std::lround((std::log10(value) - low) / (high - low) * (to - from)));
}

LogAxis AxisOver(double smallest, double largest, int from, int to) {
  LogAxis axis{std::floor(std::log10(smallest)), std::ceil(std::log10(largest)), from, to};
  if (axis.high <= axis.low) axis.high = axis.low + 1.0;
  return axis;
}

Canvas::Canvas(int width, int height, std::string plot)
    : canvas_(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT)), plot_(std::move(plot)) {
  Check(OIIO::ImageBufAlgo::fill(canvas_, {kBackground.rgb, 3}));
}

void Canvas::Check(bool ok) const {
  if (!ok) throw InputError(plot_ + ": " + canvas_.geterror());
}

void Canvas::Line(int x0, int y0, int x1, int y1, const Colour& colour) {
  Check(OIIO::ImageBufAlgo::render_line(canvas_, x0, y0, x1, y1, {colour.rgb, 3}));
}

void Canvas::Box(int x0, int y0, int x1, int y1, const Colour& colour, bool fill) {
  Check(OIIO::ImageBufAlgo::render_box(canvas_, x0, y0, x1, y1, {colour.rgb, 3}, fill));
}

void Canvas::Text(int x, int y, const std::string& text, int size, const Colour& colour,
                  OIIO::ImageBufAlgo::TextAlignX align) {
  // Text wholly off the canvas is not drawn: OpenImageIO 2.4 aborts on it.
  if (y <= 0 || y - size >= canvas_.spec().height || x < 0 || x >= canvas_.spec().width) return;
  Check(OIIO::ImageBufAlgo::render_text(canvas_, x, y, text, size, kPlotFont, {colour.rgb, 3}, align));
}

int Canvas::Legend(int x, int top, int bottom, int step, int size,
                   const std::vector<std::pair<std::string, Colour>>& entries) {
  const std::size_t room = std::size_t(std::max(1, (bottom - top) / step));
  const std::size_t shown = entries.size() <= room ? entries.size() : room - 1;
  int y = top;
  for (std::size_t i = 0; i < shown; ++i, y += step) {
    Box(x, y - 4, x + 8, y + 4, entries[i].second, true);
    Text(x + 16, y + 5, entries[i].first, size, kText);
  }
  if (shown < entries.size()) {
    Text(x, y + 5, "and " + std::to_string(entries.size() - shown) + " more", size, kMuted);
    y += step;
  }
  return y;
}

void Canvas::DecadeGrid(const LogAxis& x, const LogAxis& y, int left, int right, int top, int bottom) {
  for (int e = int(x.low); e <= int(x.high); ++e) {
    const int px = x.At(std::pow(10.0, e));
    Line(px, top, px, bottom, kGrid);
    Text(px, bottom + 20, Decade(e), 13, kMuted, OIIO::ImageBufAlgo::TextAlignX::Center);
  }
  for (int e = int(y.low); e <= int(y.high); ++e) {
    const int py = y.At(std::pow(10.0, e));
    Line(left, py, right, py, kGrid);
    Text(left - 8, py + 5, Decade(e), 13, kMuted, OIIO::ImageBufAlgo::TextAlignX::Right);
  }
}

Rgb8Image Canvas::Pixels() const {
  Rgb8Image out;
  out.width = canvas_.spec().width;
  out.height = canvas_.spec().height;
  out.bytes.resize(std::size_t(out.width) * out.height * 3);
  Check(canvas_.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, out.bytes.data()));
  return out;
}

std::string Decade(int exponent) {
  char text[16];
  std::snprintf(text, sizeof text, "1e%d", exponent);
  return text;
}

namespace {

std::vector<std::string> Words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

}  // namespace

std::string DistinguishingWords(const std::string& label, const std::vector<std::string>& labels,
                                const std::string& otherwise) {
  std::string text;
  for (const std::string& word : Words(label)) {
    bool shared = true;
    for (const std::string& other : labels) {
      const std::vector<std::string> words = Words(other);
      shared = shared && std::find(words.begin(), words.end(), word) != words.end();
    }
    if (shared || word == "backend=-") continue;
    // The method and backend by their values alone ("hpsf emulated"), the rest as NAME=VALUE.
    const bool bare = word.rfind("method=", 0) == 0 || word.rfind("backend=", 0) == 0;
    text += (text.empty() ? "" : " ") + (bare ? word.substr(word.find('=') + 1) : word);
  }
  return text.empty() ? otherwise : text;
}

}  // namespace hpsf::plot
