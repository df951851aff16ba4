// Fills sweep.tpl's ctemplate dictionary from a sweep's results (see sweep_html_report.h).
#include "tools/hpsf/sweep_html_report.h"

#include <cstdio>
#include <mutex>
#include <stdexcept>

#include <ctemplate/template.h>

#include "tools/hpsf/report_assets.h"
#include "tools/hpsf/version.h"

namespace hpsf {
namespace {

constexpr const char* kSweepTemplateKey = "hpsf/sweep.tpl";

void LoadSweepTemplate() {
  static std::once_flag once;
  std::call_once(once, [] {
    // A template that does not parse is a defect of this build, not of the user's input.
    if (!ctemplate::StringToTemplateCache(kSweepTemplateKey, report_assets::kSweepTpl, ctemplate::DO_NOT_STRIP)) {
      throw std::logic_error("hpsf sweep's HTML template (tools/hpsf/report_assets/sweep.tpl) does not parse");
    }
  });
}

// A figure for the table: 4 significant digits, or "-" where the sweep has none.
std::string Figure(const nlohmann::json& value) {
  if (!value.is_number()) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value.get<double>());
  return text;
}

// JSON inside a <script> element: "</" would end the element early, "<\/" is the same string to JSON.
std::string ScriptSafe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    out += json[i];
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') out += '\\';
  }
  return out;
}

}  // namespace

std::string RenderSweepHtml(const std::string& scene, const nlohmann::json& configurations,
                            const std::string& reference) {
  LoadSweepTemplate();
  ctemplate::TemplateDictionary page("hpsf sweep");
  page.SetValue("TITLE", "hpsf sweep " + scene);
  page.SetValue("VERSION", kHpsfVersion);
  page.SetValue("STYLE", report_assets::kReportCss);
  page.SetValue("UPLOT_CSS", report_assets::kUPlotMinCss);
  page.SetValue("UPLOT_JS", report_assets::kUPlotIifeMinJs);
  page.SetValue("SCRIPT", report_assets::kSweepJs);
  page.SetIntValue("CONFIGURATIONS", int(configurations.size()));
  page.SetValue("REFERENCE", reference);
  page.SetValue("DATA", ScriptSafe(configurations.dump()));
  for (const nlohmann::json& c : configurations) {
    ctemplate::TemplateDictionary* row = page.AddSectionDictionary("CONFIG");
    row->SetValue("ID", c.value("id", ""));
    row->SetValue("METHOD", c.value("method", ""));
    row->SetValue("SPP", Figure(c.value("spp", nlohmann::json())));
    row->SetValue("FRAMES", Figure(c.value("frames", nlohmann::json(1))));
    row->SetValue("TOTAL_S", Figure(c.value("total_s", nlohmann::json())));
    row->SetValue("RELMSE", Figure(c.value("relmse", nlohmann::json())));
    row->SetValue("SSIM", Figure(c.value("ssim", nlohmann::json())));
    row->SetValue("FIREFLIES", Figure(c.value("fireflies", nlohmann::json())));
    row->SetValue("REL_BIAS2", Figure(c.value("rel_bias2", nlohmann::json())));
    row->SetValue("REL_VARIANCE", Figure(c.value("rel_variance", nlohmann::json())));
    row->SetValue("FRONTIER", c.value("frontier", false) ? "yes" : "");
    row->SetValue("PT_AT_EQUAL_TIME", Figure(c.value("pt_relmse_at_equal_time", nlohmann::json())));
  }
  std::string html;
  ctemplate::ExpandTemplate(kSweepTemplateKey, ctemplate::DO_NOT_STRIP, &page, &html);
  return html;
}

}  // namespace hpsf
