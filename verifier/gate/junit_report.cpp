#include "verifier/gate/junit_report.h"

#include <cstdio>
#include <map>

namespace hpsf {
namespace {

// XML 1.0 text: the five markup characters escaped, control characters other than tab and newline dropped (no
// parser accepts them, even escaped).
std::string Escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\n' || c == '\t') out += c;
    }
  }
  return out;
}

std::string Seconds(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", seconds);
  return text;
}

struct Totals {
  std::size_t tests = 0, failures = 0, errors = 0;
  double seconds = 0.0;
  void Add(const GateCaseResult& r) {
    ++tests;
    failures += r.outcome == CaseOutcome::kFailed;
    errors += r.outcome == CaseOutcome::kError;
    seconds += r.seconds;
  }
  std::string Attributes() const {
    return "tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(failures) + "\" errors=\"" +
           std::to_string(errors) + "\" time=\"" + Seconds(seconds) + "\"";
  }
};

}  // namespace

std::string JUnitXml(const std::string& name, const std::vector<GateCaseResult>& results) {
  std::map<std::string, std::vector<const GateCaseResult*>> by_family;
  Totals all;
  for (const GateCaseResult& r : results) {
    by_family[r.family].push_back(&r);
    all.Add(r);
  }
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"" + Escaped(name) + "\" " +
                    all.Attributes() + ">\n";
  for (const auto& [family, cases] : by_family) {
    Totals totals;
    for (const GateCaseResult* r : cases) totals.Add(*r);
    xml += "  <testsuite name=\"" + Escaped(family) + "\" " + totals.Attributes() + ">\n";
    for (const GateCaseResult* r : cases) {
      // classname: the family and the case's first coordinate, so CI systems group cases by scene.
      const std::size_t cut = r->id.find('/', r->family.size() + 1);
      const std::string classname = r->id.substr(0, cut == std::string::npos ? r->id.size() : cut);
      xml += "    <testcase classname=\"" + Escaped(classname) + "\" name=\"" + Escaped(r->id) + "\" time=\"" +
             Seconds(r->seconds) + "\">\n";
      if (r->outcome == CaseOutcome::kFailed || r->outcome == CaseOutcome::kError) {
        const char* element = r->outcome == CaseOutcome::kFailed ? "failure" : "error";
        xml += "      <" + std::string(element) + " message=\"" + Escaped(r->message) + "\" type=\"" +
               (r->outcome == CaseOutcome::kFailed ? "contract" : "crash") + "\">" + Escaped(r->details) + "</" +
               element + ">\n";
      }
      const std::string warning = r->outcome == CaseOutcome::kWarned ? "warning: " + r->details : "";
      xml += "      <system-out>" + Escaped(warning) + "reproduce: " + Escaped(r->reproduce) +
             (r->bundle.empty() ? "" : "\nrepro bundle: " + Escaped(r->bundle)) +
             (r->fixed_point.empty() ? "" : "\naccumulation: " + Escaped(r->fixed_point)) +
             "</system-out>\n    </testcase>\n";
    }
    xml += "  </testsuite>\n";
  }
  return xml + "</testsuites>\n";
}

}  // namespace hpsf
