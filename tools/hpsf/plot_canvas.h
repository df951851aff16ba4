// What hpsf's PNG plots share (the Pareto plot, the bias and variance against filter width): a dark canvas with
// log-scaled axes and their decade grid, text in DejaVu Sans, and a colour per method. Drawn with OpenImageIO's
// ImageBufAlgo; a drawing error is an InputError naming the plot.
#ifndef HPSF_TOOLS_HPSF_PLOT_CANVAS_H
#define HPSF_TOOLS_HPSF_PLOT_CANVAS_H

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "tools/hpsf/heatmap.h"

namespace hpsf::plot {

struct Colour {
  float rgb[3];
};

inline constexpr Colour kBackground{{0.106f, 0.11f, 0.118f}}, kGrid{{0.23f, 0.24f, 0.26f}},
    kText{{0.85f, 0.86f, 0.87f}}, kMuted{{0.6f, 0.62f, 0.65f}};

// Distinct on the dark page the HTML report uses; plain path tracing light grey, the line to beat.
Colour MethodColour(const std::string& method, std::size_t index);

// The index-th of `count` series of one colour: from the colour itself down to 45% of it, so that many stay apart
// from the background.
Colour Shaded(Colour colour, std::size_t index, std::size_t count);

struct LogAxis {
  double low = 0.0, high = 1.0;  // decades, floor and ceiling of the data's log10
  int from = 0, to = 1;          // pixels
  int At(double value) const;
};
// The decades around [smallest, largest], mapped onto pixels [from, to].
LogAxis AxisOver(double smallest, double largest, int from, int to);

class Canvas {
 public:
  // `plot` names the plot in errors.
  Canvas(int width, int height, std::string plot);

  void Line(int x0, int y0, int x1, int y1, const Colour& colour);
  void Box(int x0, int y0, int x1, int y1, const Colour& colour, bool fill);
  void Text(int x, int y, const std::string& text, int size, const Colour& colour,
            OIIO::ImageBufAlgo::TextAlignX align = OIIO::ImageBufAlgo::TextAlignX::Left);
  // A legend at x from `top` down, a filled box in its colour and the label per entry, `step` pixels apart; the
  // entries that do not fit above `bottom` are counted on a last line ("and 12 more"). Returns the y below it.
  int Legend(int x, int top, int bottom, int step, int size,
             const std::vector<std::pair<std::string, Colour>>& entries);
  // The grid line and label of each decade of x over [top, bottom], of y over [left, right].
  void DecadeGrid(const LogAxis& x, const LogAxis& y, int left, int right, int top, int bottom);
  Rgb8Image Pixels() const;

 private:
  void Check(bool ok) const;
  OIIO::ImageBuf canvas_;
  std::string plot_;
};

std::string Decade(int exponent);  // "1e-3"

// A legend's label: `label`'s words without those every one of `labels` shares and without "backend=-" (a method
// with no backend), so the legend names what tells the series apart, the method and backend by their values alone;
// `otherwise` where nothing does.
std::string DistinguishingWords(const std::string& label, const std::vector<std::string>& labels,
                                const std::string& otherwise);

}  // namespace hpsf::plot

#endif  // HPSF_TOOLS_HPSF_PLOT_CANVAS_H
