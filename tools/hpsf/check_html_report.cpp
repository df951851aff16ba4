// Fills check.tpl's ctemplate dictionary from a gate run's report (see check_html_report.h).
#include "tools/hpsf/check_html_report.h"

#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <stdexcept>

#include <ctemplate/template.h>

#include "tools/hpsf/report_assets.h"
#include "tools/hpsf/version.h"

namespace hpsf {
namespace {

constexpr const char* kCheckTemplateKey = "hpsf/check.tpl";
constexpr std::array<const char*, 4> kOutcomeNames = {"pass", "warn", "fail", "error"};

void LoadCheckTemplate() {
  static std::once_flag once;
  std::call_once(once, [] {
    // A template that does not parse is a defect of this build, not of the user's input.
    if (!ctemplate::StringToTemplateCache(kCheckTemplateKey, report_assets::kCheckTpl, ctemplate::DO_NOT_STRIP)) {
      throw std::logic_error("hpsf check's HTML template (tools/hpsf/report_assets/check.tpl) does not parse");
    }
  });
}

std::string CaseSeconds(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", seconds);
  return text;
}

// The anchor of a case: its id with every character but letters and digits as '-'.
std::string CaseAnchor(const std::string& id) {
  std::string anchor = "case-";
  for (const char c : id) anchor += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return anchor;
}

std::string LinkFrom(const std::string& target, const std::string& page) {
  const std::filesystem::path folder = std::filesystem::absolute(page).parent_path();
  return std::filesystem::absolute(target).lexically_relative(folder).generic_string();
}

}  // namespace

std::string RenderCheckHtml(const CheckReport& report, const std::string& page_path) {
  LoadCheckTemplate();
  ctemplate::TemplateDictionary page("hpsf check");
  page.SetValue("TITLE", "hpsf check " + report.gate);
  page.SetValue("VERSION", kHpsfVersion);
  page.SetValue("STYLE", report_assets::kReportCss);
  page.SetIntValue("CASE_COUNT", int(report.results.size()));
  page.SetIntValue("GATE_CASES", int(report.gate_cases));
  page.SetValue("SHARD", report.shard);
  std::array<int, kOutcomeNames.size()> counts{};
  double seconds = 0.0;
  for (const GateCaseResult& r : report.results) {
    ++counts[std::size_t(r.outcome)];
    seconds += r.seconds;
  }
  page.SetValue("SECONDS", CaseSeconds(seconds));
  for (std::size_t k = 0; k < counts.size(); ++k) {
    if (counts[k] == 0) continue;
    ctemplate::TemplateDictionary* count = page.AddSectionDictionary("OUTCOME_COUNT");
    count->SetIntValue("N", counts[k]);
    count->SetValue("OUTCOME", kOutcomeNames[k]);
    count->SetValue("OUTCOME_CLASS", kOutcomeNames[k]);
  }
  for (const FamilyTotals& f : report.Families()) {
    ctemplate::TemplateDictionary* row = page.AddSectionDictionary("FAMILY");
    row->SetValue("FAMILY", f.family);
    row->SetIntValue("CASES", int(f.cases));
    row->SetIntValue("PASSED", int(f.passed));
    row->SetIntValue("WARNED", int(f.warned));
    row->SetIntValue("FAILED", int(f.failed));
    row->SetIntValue("ERRORS", int(f.errors));
    row->SetValue("SECONDS", CaseSeconds(f.seconds));
  }
  for (const GateCaseResult& r : report.results) {
    ctemplate::TemplateDictionary* row = page.AddSectionDictionary("CASE");
    const char* outcome = kOutcomeNames[std::size_t(r.outcome)];
    row->SetValue("OUTCOME", outcome);
    row->SetValue("OUTCOME_CLASS", outcome);
    row->SetValue("ANCHOR", CaseAnchor(r.id));
    row->SetIntValue("INDEX", int(r.index + 1));
    row->SetValue("ID", r.id);
    row->SetValue("SECONDS", CaseSeconds(r.seconds));
    row->SetValue("REPRODUCE", r.reproduce);
    if (!r.fixed_point.empty()) row->AddSectionDictionary("FIXED_POINT")->SetValue("FIXED_POINT", r.fixed_point);
    if (r.outcome != CaseOutcome::kPassed) {
      ctemplate::TemplateDictionary* problem = row->AddSectionDictionary("PROBLEM");
      problem->SetValue("MESSAGE", r.message);
      problem->SetValue("DETAILS", r.details);
    }
    if (!r.bundle.empty()) row->AddSectionDictionary("BUNDLE")->SetValue("BUNDLE", r.bundle);
    if (!r.html.empty()) row->AddSectionDictionary("CASE_REPORT")->SetValue("HREF", LinkFrom(r.html, page_path));
  }
  std::string html;
  if (!ctemplate::ExpandTemplate(kCheckTemplateKey, ctemplate::DO_NOT_STRIP, &page, &html)) {
    throw std::logic_error("hpsf check's HTML template did not expand");
  }
  return html;
}

}  // namespace hpsf
