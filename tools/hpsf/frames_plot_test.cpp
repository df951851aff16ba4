// The plot of relMSE against frames (tools/hpsf/frames_plot.h) and the legend every plot shares
// (tools/hpsf/plot_canvas.h): more series than the legend has room for are counted, not drawn past the canvas
// (OpenImageIO aborted on text below it: a sweep of 72 sequences crashed before the legend was bounded).
#include "tools/hpsf/frames_plot.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "tools/hpsf/plot_canvas.h"

namespace hpsf {
namespace {

TEST(FramesPlot, ManySeriesFitTheCanvas) {
  std::vector<FrameSeries> series;
  for (int i = 0; i < 72; ++i) {
    FrameSeries s{"method=hpsf backend=reference spp=" + std::to_string(i + 1), "hpsf", {}};
    for (int f = 1; f <= 64; ++f) s.relmse.push_back(0.1 / (f * (i + 1)));
    series.push_back(s);
  }
  const Rgb8Image image = RenderFramesPlot("cornell", series);
  EXPECT_EQ(image.width, 960);
  EXPECT_EQ(image.height, 600);
}

TEST(FramesPlot, NoPositiveRelMseIsAnInputError) {
  EXPECT_THROW(RenderFramesPlot("cornell", {{"method=pt backend=- spp=1", "pt", {0.0, -1.0}}}), InputError);
}

TEST(PlotLegend, CountsTheEntriesItHasNoRoomFor) {
  plot::Canvas canvas(200, 100, "a test plot");
  std::vector<std::pair<std::string, plot::Colour>> entries(30, {"entry", plot::kText});
  // Rows 20 apart from y 10 to 90: four rows, three entries and the count of the other 27.
  EXPECT_EQ(canvas.Legend(10, 10, 90, 20, 12, entries), 90);
  entries.resize(3);
  EXPECT_EQ(canvas.Legend(10, 10, 90, 20, 12, entries), 70);
  canvas.Text(10, 500, "below the canvas", 12, plot::kText);  // not drawn, no abort
}

TEST(PlotLegend, LabelsNameWhatTellsTheSeriesApart) {
  const std::vector<std::string> labels = {"method=pt backend=- spp=1 frames=4",
                                           "method=hpsf backend=emulated spp=1 frames=4"};
  EXPECT_EQ(plot::DistinguishingWords(labels[0], labels, "pt"), "pt");
  EXPECT_EQ(plot::DistinguishingWords(labels[1], labels, "hpsf"), "hpsf emulated");
  EXPECT_EQ(plot::DistinguishingWords(labels[1], {labels[1]}, "hpsf"), "hpsf");
}

}  // namespace
}  // namespace hpsf
