// The self-contained HTML report of `hpsf diff --html` and (one section per case) `hpsf golden check`: per
// comparison A, B and the error heatmap side by side, a wipe between A and B, an exposure control, the verdict
// with its explanation, every metric and the metadata that differs. One file that opens anywhere with no
// network: the images are embedded (A and B as linear float16 for the exposure control, the heatmap as a PNG
// data: URI), and so are the style and script (tools/hpsf/report_assets, compiled into the binary). The page's
// structure is a ctemplate template that escapes every string for the place it stands in, so a path or a
// metadata value from a file cannot become markup.
#ifndef HPSF_TOOLS_HPSF_HTML_REPORT_H
#define HPSF_TOOLS_HPSF_HTML_REPORT_H

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "verifier/metrics/channel_image.h"
#include "verifier/metrics/image_comparison.h"

namespace hpsf {

struct ReportEntry {
  std::string title;
  const ChannelImage* a = nullptr;  // borrowed: must outlive RenderHtmlReport
  const ChannelImage* b = nullptr;
  std::string a_label, b_label;  // e.g. the paths
  ImageComparison comparison;
  // Anything more to show, e.g. a statistical test's result: an object's members become a key/value table.
  std::optional<nlohmann::json> extra;
};

std::string RenderHtmlReport(const std::string& title, const std::vector<ReportEntry>& entries);

// Writes under a temporary name and renames it into place; InputError naming the path on failure.
void WriteHtmlReport(const std::string& path, const std::string& html);

// Above this many pixels an image is embedded downsampled (and the page says so): A and B as float16 cost 8 bytes
// of base64 a pixel each, so a 1080p pair would be 33 MB.
inline constexpr std::size_t kReportMaxPixels = 1u << 20;

// What the page shows of one image: its colour as linear RGB, box-filtered down by `factor` when it has more than
// max_pixels pixels (each shown pixel the mean of a factor x factor block; blocks at the right and bottom edges
// may be partial).
struct ShownImage {
  int width = 0, height = 0, factor = 1;
  std::vector<float> rgb;  // width * height * 3
  std::string channels;    // which channels became R, G, B, e.g. "R,G,B" or "Y as grey"
};

ShownImage ShowImage(const ChannelImage& image, std::size_t max_pixels = kReportMaxPixels);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_HTML_REPORT_H
