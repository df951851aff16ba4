// The error heatmap of `hpsf diff`: per pixel the largest |A - B| over the colour channels, through the
// perceptually uniform "inferno" colour map of OpenImageIO (ImageBufAlgo::color_map) from 0 to the 99th
// percentile of those errors (larger ones in the top colour), with a legend strip below naming the scale. Small
// images are enlarged by whole pixels. Returned as 8-bit RGB for the report, or written as a PNG.
#ifndef HPSF_TOOLS_HPSF_HEATMAP_H
#define HPSF_TOOLS_HPSF_HEATMAP_H

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "verifier/metrics/channel_image.h"

namespace hpsf {

struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> bytes;  // width * height * 3
};

// The colour map's range: black is 0, the top colour `top` (the 99th percentile) and above; `largest` is the
// largest finite error. The HTML report repeats it as text, since the legend shrinks with a large image.
struct HeatmapScale {
  float top = 0.0f, largest = 0.0f;
};

Rgb8Image RenderHeatmap(const ChannelImage& a, const ChannelImage& b, HeatmapScale* scale_out = nullptr);

// The legend strip's three texts: the colour map's low end, what it shows, its top.
struct ColourMapLegend {
  std::string low, quantity, top;
  double quantity_at = 1.0 / 3.0;  // where the quantity's text is centred, as a fraction of the width
};
// Values scaled to [0, 1] already (image_width x image_height, row-major) through the same colour map and legend: the
// heatmap's, and other debug images' (tools/hpsf/cell_variance_map.h).
Rgb8Image RenderColourMap(std::span<const float> unit_values, int image_width, int image_height,
                          const ColourMapLegend& legend);

// The image as PNG file bytes, for a data URI.
std::string EncodePng(const Rgb8Image& image);

// Writes the PNG under a temporary name and renames it into place; InputError naming the path on failure.
void WritePng(const std::string& path, const Rgb8Image& image);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_HEATMAP_H
