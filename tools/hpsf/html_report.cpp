// The HTML report: fills report.tpl's ctemplate dictionary from the comparisons (see html_report.h for what the
// page shows and why it is one self-contained file).
#include "tools/hpsf/html_report.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <stdexcept>

#include <Imath/half.h>
#include <OpenImageIO/strutil.h>
#include <ctemplate/template.h>

#include "core/error.h"
#include "tools/hpsf/heatmap.h"
#include "tools/hpsf/report_assets.h"
#include "tools/hpsf/version.h"
#include "verifier/metrics/diff_verdict.h"

namespace hpsf {
namespace {

constexpr const char* kTemplateKey = "hpsf/report.tpl";
// The heatmap's own enlargement rule (heatmap.cpp): A and B are enlarged by the same whole factor, so that the
// three panels line up pixel for pixel.
constexpr int kPanelMinimumWidth = 360;
constexpr int kLegibleLegendWidth = 480;
constexpr int kWipeWidth = 576;  // the wipe enlarges a small image further, for a close look

void LoadTemplate() {
  static std::once_flag once;
  std::call_once(once, [] {
    // A template that does not parse is a defect of this build, not of the user's input.
    if (!ctemplate::StringToTemplateCache(kTemplateKey, report_assets::kReportTpl, ctemplate::DO_NOT_STRIP)) {
      throw std::logic_error("the HTML report's template (tools/hpsf/report_assets/report.tpl) does not parse");
    }
  });
}

std::string FormatNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[48];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string VerdictClass(DiffVerdict verdict) {
  std::string name = ToString(verdict);
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return name;
}

// Linear values as little-endian float16, base64: half the size of float32, and 11 significant bits are more
// than an 8-bit display shows at any exposure. Finite values beyond float16's range are clamped to its largest,
// so that a firefly shows white rather than turning into infinity (which the page draws black, as srgb.h does).
std::string EncodeHalfs(const std::vector<float>& values) {
  constexpr float kHalfMax = 65504.0f;
  std::string bytes;
  bytes.reserve(values.size() * 2);
  for (float v : values) {
    const float clamped = std::isfinite(v) ? std::clamp(v, -kHalfMax, kHalfMax) : v;
    const std::uint16_t bits = Imath::half(clamped).bits();
    bytes.push_back(char(bits & 0xff));
    bytes.push_back(char(bits >> 8));
  }
  return OIIO::Strutil::base64_encode(bytes);
}

struct MetricRow {
  std::string name, value, note;
  std::optional<DiffMetric> metric;  // the verdict's metric, when this row is one
};

std::vector<MetricRow> MetricRows(const ImageComparison& c) {
  const ImageMetrics& m = c.metrics;
  char place[160];
  std::snprintf(place, sizeof place, "at (%d, %d), channel %s", m.max_x, m.max_y, m.max_channel.c_str());
  return {
      {"values compared", std::to_string(m.values), "pixels \u00d7 colour channels", std::nullopt},
      {"non-finite mismatches", std::to_string(m.nonfinite_mismatches),
       "not finite in one image and not the same value in the other", std::nullopt},
      {"MSE", FormatNumber(m.mse), "", DiffMetric::kMse},
      {"RMSE", FormatNumber(m.rmse), "", DiffMetric::kRmse},
      {"relMSE", FormatNumber(m.relmse), "\u03a3 d\u00b2 / (B\u00b2 + 0.01) / n", DiffMetric::kRelMse},
      {"PSNR", FormatNumber(m.psnr) + " dB", "peak " + FormatNumber(m.peak) + " (largest in A or B, at least 1)",
       DiffMetric::kPsnr},
      {"mean |A\u2212B|", FormatNumber(m.mean_abs), "", DiffMetric::kMeanAbs},
      {"max |A\u2212B|", FormatNumber(m.max_abs), place, DiffMetric::kMaxAbs},
      {"p" + FormatNumber(m.percentile_rank) + " |A\u2212B|", FormatNumber(m.percentile), "nearest rank",
       DiffMetric::kPercentile},
      {"pixels over " + FormatNumber(m.pixel_threshold), FormatNumber(m.fraction_over),
       FormatNumber(100.0 * m.fraction_over) + "% of pixels have a largest |A\u2212B| above it",
       DiffMetric::kFractionOver},
      {"SSIM", c.ssim ? FormatNumber(*c.ssim) : "not computed", "of the sRGB previews (hpsf diff --ssim)",
       DiffMetric::kSsim},
  };
}

std::string JudgedNote(const DiffThresholds& t) {
  const char* worse = HigherIsBetter(t.metric) ? "below" : "above";
  return std::string("judged: WARN ") + worse + " " + FormatNumber(t.warn) + ", FAIL " + worse + " " +
         FormatNumber(t.fail);
}

void FillImages(const ReportEntry& entry, ctemplate::TemplateDictionary* d) {
  const ShownImage a = ShowImage(*entry.a);
  const ShownImage b = ShowImage(*entry.b);
  d->SetIntValue("WIDTH", entry.a->width);
  d->SetIntValue("HEIGHT", entry.a->height);
  d->SetIntValue("SHOWN_WIDTH", a.width);
  d->SetIntValue("SHOWN_HEIGHT", a.height);
  d->SetIntValue("FACTOR", a.factor);
  if (a.factor > 1) d->ShowSection("DOWNSAMPLED");
  d->SetValue("SHOWN_CHANNELS", a.channels == b.channels ? a.channels : "A " + a.channels + ", B " + b.channels);
  d->SetValue("A_PIXELS", EncodeHalfs(a.rgb));
  d->SetValue("B_PIXELS", EncodeHalfs(b.rgb));
  std::string channels;
  for (const std::string& name : entry.a->channels) channels += (channels.empty() ? "" : ",") + name;
  d->SetValue("CHANNELS", channels);

  const int width = entry.a->width;
  const int zoom = std::clamp(kPanelMinimumWidth / width, 1, 8);
  d->SetIntValue("PANEL_WIDTH", width * zoom);
  d->SetValue("PANEL_PIXELATED", zoom > 1 ? "pixelated" : "");
  const int wipe_zoom = std::clamp(kWipeWidth / width, 1, 16);
  d->SetIntValue("WIPE_WIDTH", width * wipe_zoom);
  d->SetValue("WIPE_PIXELATED", wipe_zoom > 1 ? "pixelated" : "");

  HeatmapScale scale;
  const Rgb8Image heatmap = RenderHeatmap(*entry.a, *entry.b, &scale);
  // The heatmap's own legend stays legible up to about a panel's width; a larger heatmap is shrunk to fit, so
  // the page repeats its scale as text.
  if (heatmap.width > kLegibleLegendWidth) {
    ctemplate::TemplateDictionary* legend = d->AddSectionDictionary("HEATMAP_LEGEND");
    legend->SetValue("HEATMAP_TOP", FormatNumber(scale.top));
    if (scale.largest > scale.top) {
      legend->AddSectionDictionary("HEATMAP_CLIPPED")->SetValue("HEATMAP_LARGEST", FormatNumber(scale.largest));
    }
  }
  d->SetValue("HEATMAP_URI", "data:image/png;base64," + OIIO::Strutil::base64_encode(EncodePng(heatmap)));
  d->SetIntValue("HEATMAP_WIDTH", heatmap.width);
  d->SetIntValue("HEATMAP_HEIGHT", heatmap.height);
}

void FillTables(const ReportEntry& entry, ctemplate::TemplateDictionary* d) {
  const ImageComparison& c = entry.comparison;
  for (const MetricRow& row : MetricRows(c)) {
    ctemplate::TemplateDictionary* r = d->AddSectionDictionary("METRIC_ROW");
    const bool judged = row.metric == c.thresholds.metric;
    r->SetValue("NAME", row.name);
    r->SetValue("VALUE", row.value);
    r->SetValue("NOTE", judged ? (row.note.empty() ? "" : row.note + "; ") + JudgedNote(c.thresholds) : row.note);
    r->SetValue("ROW_CLASS", judged ? "judged" : "");
  }

  if (c.metadata.empty()) {
    ctemplate::TemplateDictionary* same = d->AddSectionDictionary("METADATA_SAME");
    if (!entry.a->metadata.empty())
      same->AddSectionDictionary("METADATA_COUNT")->SetIntValue("KEYS", int(entry.a->metadata.size()));
  }
  for (const MetadataDifference& difference : c.metadata) {
    ctemplate::TemplateDictionary* r = d->AddSectionDictionary("METADATA_ROW");
    r->SetValue("KEY", difference.key);
    r->SetValue("A", difference.a.value_or("(absent)"));
    r->SetValue("A_CLASS", difference.a ? "" : "absent");
    r->SetValue("B", difference.b.value_or("(absent)"));
    r->SetValue("B_CLASS", difference.b ? "" : "absent");
  }

  if (entry.extra) {
    ctemplate::TemplateDictionary* extra = d->AddSectionDictionary("EXTRA");
    extra->SetValue("EXTRA_CAPTION", "more results");
    const auto add_row = [extra](const std::string& key, const nlohmann::json& value) {
      ctemplate::TemplateDictionary* r = extra->AddSectionDictionary("EXTRA_ROW");
      r->SetValue("KEY", key);
      r->SetValue("VALUE", value.is_string() ? value.get<std::string>() : value.dump());
    };
    if (entry.extra->is_object()) {
      for (const auto& [key, value] : entry.extra->items()) add_row(key, value);
    } else {
      add_row("value", *entry.extra);
    }
  }
}

}  // namespace

ShownImage ShowImage(const ChannelImage& image, std::size_t max_pixels) {
  ShownImage shown;
  std::array<int, 3> source = {image.ChannelIndex("R"), image.ChannelIndex("G"), image.ChannelIndex("B")};
  if (source == std::array<int, 3>{-1, -1, -1}) {
    // No R, G or B (e.g. a luminance image): the first colour channel, as grey.
    for (std::size_t c = 0; c < image.channels.size() && source[0] < 0; ++c) {
      if (!IsColorChannel(image.channels[c])) continue;
      source = {int(c), int(c), int(c)};
      shown.channels = image.channels[c] + " as grey";
    }
    if (source[0] < 0) shown.channels = "no colour channel (black)";
  } else {
    for (int s : source) shown.channels += (shown.channels.empty() ? "" : ",") + (s < 0 ? "0" : image.channels[s]);
  }

  const auto shrunk = [](int size, int factor) { return (size + factor - 1) / factor; };
  while (std::size_t(shrunk(image.width, shown.factor)) * std::size_t(shrunk(image.height, shown.factor)) >
         max_pixels) {
    ++shown.factor;
  }
  const int f = shown.factor;
  shown.width = shrunk(image.width, f);
  shown.height = shrunk(image.height, f);
  shown.rgb.assign(std::size_t(shown.width) * std::size_t(shown.height) * 3, 0.0f);
  for (int y = 0; y < shown.height; ++y) {
    for (int x = 0; x < shown.width; ++x) {
      const int x_end = std::min(image.width, (x + 1) * f), y_end = std::min(image.height, (y + 1) * f);
      for (int c = 0; c < 3; ++c) {
        if (source[c] < 0) continue;
        double sum = 0.0;
        for (int sy = y * f; sy < y_end; ++sy) {
          for (int sx = x * f; sx < x_end; ++sx) {
            sum += image.At(std::size_t(sy) * std::size_t(image.width) + std::size_t(sx), std::size_t(source[c]));
          }
        }
        shown.rgb[(std::size_t(y) * std::size_t(shown.width) + std::size_t(x)) * 3 + std::size_t(c)] =
            float(sum / double((x_end - x * f) * (y_end - y * f)));
      }
    }
  }
  return shown;
}

std::string RenderHtmlReport(const std::string& title, const std::vector<ReportEntry>& entries) {
  LoadTemplate();
  ctemplate::TemplateDictionary page("hpsf report");
  page.SetValue("TITLE", title);
  page.SetValue("VERSION", kHpsfVersion);
  page.SetValue("STYLE", report_assets::kReportCss);
  page.SetValue("SCRIPT", report_assets::kReportJs);
  page.SetIntValue("ENTRY_COUNT", int(entries.size()));
  page.SetValue("ENTRY_NOUN", entries.size() == 1 ? "comparison" : "comparisons");
  for (DiffVerdict verdict : {DiffVerdict::kFail, DiffVerdict::kWarn, DiffVerdict::kPass}) {
    const auto n = std::count_if(entries.begin(), entries.end(),
                                 [verdict](const ReportEntry& e) { return e.comparison.verdict == verdict; });
    if (n == 0) continue;
    ctemplate::TemplateDictionary* count = page.AddSectionDictionary("VERDICT_COUNT");
    count->SetIntValue("N", int(n));
    count->SetValue("VERDICT", ToString(verdict));
    count->SetValue("VERDICT_CLASS", VerdictClass(verdict));
  }
  // One comparison needs no table of contents; a golden check's many do.
  ctemplate::TemplateDictionary* summary = entries.size() > 1 ? page.AddSectionDictionary("SUMMARY") : nullptr;

  for (std::size_t i = 0; i < entries.size(); ++i) {
    const ReportEntry& entry = entries[i];
    if (!entry.a || !entry.b) throw std::invalid_argument("RenderHtmlReport: entry '" + entry.title + "' has no image");
    const ImageComparison& c = entry.comparison;
    const std::string anchor = "case-" + std::to_string(i + 1);

    if (summary) {
      ctemplate::TemplateDictionary* row = summary->AddSectionDictionary("SUMMARY_ROW");
      row->SetValue("ANCHOR", anchor);
      row->SetValue("TITLE", entry.title);
      row->SetValue("VERDICT", ToString(c.verdict));
      row->SetValue("VERDICT_CLASS", VerdictClass(c.verdict));
      row->SetValue("METRIC", ToString(c.thresholds.metric));
      row->SetValue("VALUE", FormatNumber(c.value));
    }

    ctemplate::TemplateDictionary* d = page.AddSectionDictionary("ENTRY");
    d->SetValue("ANCHOR", anchor);
    d->SetValue("TITLE", entry.title);
    d->SetValue("VERDICT", ToString(c.verdict));
    d->SetValue("VERDICT_CLASS", VerdictClass(c.verdict));
    d->SetValue("EXPLANATION", c.Explanation());
    d->SetValue("A_LABEL", entry.a_label);
    d->SetValue("B_LABEL", entry.b_label);
    FillImages(entry, d);
    FillTables(entry, d);
  }

  std::string html;
  if (!ctemplate::ExpandTemplate(kTemplateKey, ctemplate::DO_NOT_STRIP, &page, &html)) {
    throw std::logic_error("the HTML report's template did not expand");
  }
  return html;
}

void WriteHtmlReport(const std::string& path, const std::string& html) {
  const std::filesystem::path target(path);
  const std::filesystem::path temporary = target.parent_path() / ("." + target.filename().string() + ".partial.html");
  std::error_code error;
  if (!target.parent_path().empty()) std::filesystem::create_directories(target.parent_path(), error);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(html.data(), std::streamsize(html.size()));
    out.close();
    if (!out) {
      std::filesystem::remove(temporary, error);
      throw InputError(path + ": cannot write the report");
    }
  }
  std::filesystem::rename(temporary, target, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw InputError(path + ": cannot put the report in place: " + error.message());
  }
}

}  // namespace hpsf
