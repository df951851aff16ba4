#include "tools/hpsf/heatmap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "core/error.h"
#include "verifier/metrics/image_metrics.h"

namespace hpsf {
namespace {

// Debian's fonts-dejavu-core (scripts/install-deps.sh); OpenImageIO's own default font is not packaged.
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr int kLegendHeight = 44;
constexpr int kMinimumWidth = 360;  // room for the legend's text under a small image

float LargestColourError(const ChannelImage& a, const ChannelImage& b, std::size_t pixel) {
  float largest = 0.0f;
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    if (!IsColorChannel(a.channels[c])) continue;
    const float d = std::abs(a.At(pixel, c) - b.At(pixel, c));
    largest = std::isnan(d) ? INFINITY : std::max(largest, d);
  }
  return largest;
}

void Check(bool ok, const OIIO::ImageBuf& buffer, const char* step) {
  if (!ok) throw InputError(std::string("heatmap: ") + step + ": " + buffer.geterror());
}

}  // namespace

Rgb8Image RenderHeatmap(const ChannelImage& a, const ChannelImage& b, HeatmapScale* scale_out) {
  CheckComparable(a, b);
  std::vector<float> errors(a.PixelCount());
  float largest = 0.0f;
  for (std::size_t p = 0; p < errors.size(); ++p) {
    errors[p] = LargestColourError(a, b, p);
    if (std::isfinite(errors[p])) largest = std::max(largest, errors[p]);
  }
  // The scale tops out at the 99th percentile of the pixel errors, so one firefly does not turn the rest black;
  // larger errors, and non-finite ones (NaN against a number), show in the top colour.
  std::vector<float> sorted;
  for (float e : errors) {
    if (std::isfinite(e)) sorted.push_back(e);
  }
  float scale = 0.0f;
  if (!sorted.empty()) {
    const std::size_t k = std::min(sorted.size() - 1, std::size_t(std::ceil(0.99 * double(sorted.size()))) - 1);
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    scale = sorted[k] > 0.0f ? sorted[k] : largest;
  }
  if (scale_out) *scale_out = HeatmapScale{scale, largest};
  for (float& e : errors) e = std::isfinite(e) ? (scale > 0.0f ? std::min(e / scale, 1.0f) : 0.0f) : 1.0f;

  char top[96];
  if (largest > scale) {
    std::snprintf(top, sizeof top, ">= %.3g (max %.3g)", double(scale), double(largest));
  } else {
    std::snprintf(top, sizeof top, "%.3g", double(scale));
  }
  return RenderColourMap(errors, a.width, a.height, {"0", "max |A-B| per pixel", top});
}

Rgb8Image RenderColourMap(std::span<const float> unit_values, int image_width, int image_height,
                          const ColourMapLegend& legend) {
  // Small images are enlarged by whole pixels (no filtering) so that a one-pixel value stays visible.
  const int zoom = std::clamp(kMinimumWidth / image_width, 1, 8);
  const int shown_width = image_width * zoom, shown_height = image_height * zoom;
  std::vector<float> zoomed(std::size_t(shown_width) * std::size_t(shown_height));
  for (int y = 0; y < shown_height; ++y) {
    for (int x = 0; x < shown_width; ++x) {
      zoomed[std::size_t(y) * shown_width + x] =
          unit_values[std::size_t(y / zoom) * std::size_t(image_width) + std::size_t(x / zoom)];
    }
  }
  OIIO::ImageBuf value_image(OIIO::ImageSpec(shown_width, shown_height, 1, OIIO::TypeDesc::FLOAT), zoomed.data());
  const OIIO::ImageBuf heat = OIIO::ImageBufAlgo::color_map(value_image, 0, "inferno");
  Check(!heat.has_error(), heat, "colour map");

  const int width = std::max(shown_width, kMinimumWidth);
  OIIO::ImageBuf canvas(OIIO::ImageSpec(width, shown_height + kLegendHeight, 3, OIIO::TypeDesc::FLOAT));
  const float background[3] = {0.12f, 0.12f, 0.12f};
  Check(OIIO::ImageBufAlgo::fill(canvas, background), canvas, "background");
  Check(OIIO::ImageBufAlgo::paste(canvas, 0, 0, 0, 0, heat), canvas, "image");

  const int bar_width = width - 20;
  std::vector<float> ramp(std::size_t(bar_width) * 12);
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < bar_width; ++x) ramp[std::size_t(y) * bar_width + x] = float(x) / float(bar_width - 1);
  }
  OIIO::ImageBuf ramp_image(OIIO::ImageSpec(bar_width, 12, 1, OIIO::TypeDesc::FLOAT), ramp.data());
  const OIIO::ImageBuf bar = OIIO::ImageBufAlgo::color_map(ramp_image, 0, "inferno");
  Check(OIIO::ImageBufAlgo::paste(canvas, 10, shown_height + 6, 0, 0, bar), canvas, "legend");

  const float white[3] = {1.0f, 1.0f, 1.0f};
  const int baseline = shown_height + kLegendHeight - 8;
  using Align = OIIO::ImageBufAlgo::TextAlignX;
  Check(OIIO::ImageBufAlgo::render_text(canvas, 10, baseline, legend.low, 13, kFont, white, Align::Left), canvas,
        "text");
  Check(OIIO::ImageBufAlgo::render_text(canvas, int(width * legend.quantity_at), baseline, legend.quantity, 13, kFont,
                                        white, Align::Center),
        canvas, "text");
  Check(OIIO::ImageBufAlgo::render_text(canvas, width - 10, baseline, legend.top, 13, kFont, white, Align::Right),
        canvas, "text");

  Rgb8Image out;
  out.width = width;
  out.height = shown_height + kLegendHeight;
  out.bytes.resize(std::size_t(out.width) * out.height * 3);
  Check(canvas.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, out.bytes.data()), canvas, "pixels");
  return out;
}

std::string EncodePng(const Rgb8Image& image) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create("memory.png");
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  if (!out || !out->set_ioproxy(&memory) || !out->open("memory.png", spec) ||
      !out->write_image(OIIO::TypeDesc::UINT8, image.bytes.data()) || !out->close()) {
    throw InputError(std::string("cannot encode a PNG: ") + (out ? out->geterror() : OIIO::geterror()));
  }
  return std::string(bytes.begin(), bytes.end());
}

void WritePng(const std::string& path, const Rgb8Image& image) {
  const std::filesystem::path target(path);
  // Appended in place: GCC 12 at -O3 reports a false -Wrestrict on "literal" + std::string&& (GCC bug 105651).
  const std::filesystem::path temporary =
      target.parent_path() / std::string(".").append(target.filename().string()).append(".partial.png");
  std::error_code error;
  if (!target.parent_path().empty()) std::filesystem::create_directories(target.parent_path(), error);
  auto out = OIIO::ImageOutput::create(temporary.string());
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  if (!out || !out->open(temporary.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, image.bytes.data()) ||
      !out->close()) {
    std::filesystem::remove(temporary, error);
    throw InputError(path + ": cannot write the image: " + (out ? out->geterror() : OIIO::geterror()));
  }
  std::filesystem::rename(temporary, target, error);
  if (error) throw InputError(path + ": cannot put the image in place: " + error.message());
}

}  // namespace hpsf
