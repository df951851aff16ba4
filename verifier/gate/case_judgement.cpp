#include "verifier/gate/case_judgement.h"

#include <cstdio>
#include <vector>

#include "core/error.h"
#include "verifier/gate/diff_thresholds.h"

namespace hpsf {
namespace {

using nlohmann::json;

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

// A crosscheck report's failures, each "level N name: failure".
std::vector<std::string> ContractFailures(const json& report) {
  std::vector<std::string> lines;
  if (!report.contains("levels")) return lines;
  for (const json& level : report["levels"]) {
    if (!level.value("applicable", false) || level.value("passed", true)) continue;
    const std::string head =
        "level " + std::to_string(level["level"].get<int>()) + " " + level["name"].get<std::string>();
    for (const json& failure : level["failures"]) lines.push_back(head + ": " + failure.get<std::string>());
  }
  return lines;
}

std::string RateLine(const std::string& what, const json& rate) {
  return what + ": " + Number(rate["rate"].get<double>()) + " (" + std::to_string(rate["events"].get<std::uint64_t>()) +
         " of " + std::to_string(rate["trials"].get<std::uint64_t>()) + ") above its theory " +
         Number(rate["theory"].get<double>()) + ", interval [" + Number(rate["interval"][0].get<double>()) + ", " +
         Number(rate["interval"][1].get<double>()) + "]";
}

// A stats report's rates above their theory and rejected jitter tests.
std::vector<std::string> StatisticsWarnings(const json& report) {
  std::vector<std::string> lines;
  for (const json& f : report.value("probe_failures", json::array())) {
    if (f["failures"]["exceeds_theory"].get<bool>()) {
      lines.push_back(
          RateLine("probe failures at probe limit " + std::to_string(f["probe_limit"].get<int>()), f["failures"]));
    }
  }
  for (const json& a : report.value("aliases", json::array())) {
    if (a["aliases"]["exceeds_theory"].get<bool>()) {
      lines.push_back(RateLine("aliases at " + std::to_string(a["fingerprint_bits"].get<int>()) + " fingerprint bits",
                               a["aliases"]));
    }
  }
  for (const json& t : report.value("jitter", json::array())) {
    if (t["rejected"].get<bool>()) {
      lines.push_back("jitter test " + t["test"].get<std::string>() + " rejected: p " +
                      Number(t["p_value"].get<double>()) + " over " +
                      std::to_string(t["samples"].get<std::uint64_t>()) + " samples");
    }
  }
  return lines;
}

// A golden check's comparisons that did not pass, "case on backend: explanation" (which begins with the verdict).
std::vector<std::string> GoldenProblems(const json& report) {
  std::vector<std::string> lines;
  for (const json& check : report.value("checks", json::array())) {
    const std::string verdict = check["verdict"].get<std::string>();
    if (verdict == ToString(DiffVerdict::kPass)) continue;  // as `hpsf golden check` writes it
    lines.push_back(check["case"].get<std::string>() + " on " + check["backend"].get<std::string>() + ": " +
                    check["explanation"].get<std::string>());
    for (const json& artifact : check["artifacts"]) lines.push_back("  left " + artifact.get<std::string>());
  }
  return lines;
}

// A fuzz failure: where it was found, what it shrank to, and the shrunk case's contract failures.
std::vector<std::string> FuzzFailure(const json& report) {
  if (!report.contains("failure")) return {};
  const json& f = report["failure"];
  std::vector<std::string> lines = ContractFailures(f["report"]);
  const std::string where = "at run " + std::to_string(f["run"].get<std::uint64_t>()) + " (" +
                            f["family"].get<std::string>() + ", " + std::to_string(f["records"].get<std::uint64_t>()) +
                            " records, shrunk to " + std::to_string(f["shrunk_records"].get<std::uint64_t>()) + ")";
  if (lines.empty()) lines.push_back("a failure");
  lines.front() += " " + where;
  lines.push_back("shrunk case: " + f["shrunk_case"].get<std::string>());
  return lines;
}

// A judge's failures over its captures, each "CAPTURE: level N name: failure".
std::vector<std::string> CaptureFailures(const json& report) {
  std::vector<std::string> lines;
  for (const json& c : report.value("captures", json::array())) {
    for (const std::string& line : ContractFailures(c["report"])) {
      lines.push_back(c["capture"].get<std::string>() + ": " + line);
    }
  }
  return lines;
}

std::vector<std::string> Problems(const std::string& family, const json& report) {
  if (family == "crosscheck") return ContractFailures(report);
  if (family == "statistics") return StatisticsWarnings(report);
  if (family == "golden") return GoldenProblems(report);
  if (family == "fuzz") return FuzzFailure(report);
  if (family == "captures") return CaptureFailures(report);
  return {};
}

}  // namespace

namespace {

// What the command's report states of its accumulation and F: a cross-check's mode and F, a fuzz run's range of F.
std::string FixedPoint(const std::string& family, const json& report) {
  if (family == "crosscheck" && report.contains("fixed_point_bits") && report.contains("accumulation")) {
    const std::string mode = report["accumulation"].get<std::string>();
    const std::string moments =
        report.contains("square_bits")
            ? ", second moments" +
                  (mode == "fixed64" ? " at G " + std::to_string(report["square_bits"].get<int>()) : "")
            : "";
    return (mode == "fixed64" ? mode + ", F " + std::to_string(report["fixed_point_bits"].get<int>()) : mode) + moments;
  }
  // A statistics case with --second-moments: the variance of its cells in one line.
  if (family == "statistics" && report.contains("cell_variance")) {
    const json& v = report["cell_variance"];
    char line[160];
    std::snprintf(
        line, sizeof line, "second moments: cell variance median %.3g, 90%% %.3g; %llu of %llu cells resolved",
        v["median_variance"].get<double>(), v["p90_variance"].get<double>(),
        (unsigned long long)v["resolved"].get<std::uint64_t>(), (unsigned long long)v["cells"].get<std::uint64_t>());
    return line;
  }
  if (family == "captures" && report.contains("captures") && !report["captures"].empty()) {
    return FixedPoint("crosscheck", report["captures"][0]["report"]);  // the first frame's: a folder is one table
  }
  if (family == "fuzz" && report.contains("fixed_point_bits") && report["fixed_point_bits"].is_object()) {
    const int low = report["fixed_point_bits"]["min"].get<int>(), high = report["fixed_point_bits"]["max"].get<int>();
    return "fixed64 at F " + (low == high ? std::to_string(low) : std::to_string(low) + " to " + std::to_string(high));
  }
  return "";
}

}  // namespace

void JudgeCase(const CaseRun& run, GateCaseResult& r) {
  r.message.clear();
  r.details.clear();
  r.fixed_point.clear();
  try {
    if (run.report) r.fixed_point = FixedPoint(r.family, *run.report);
  } catch (const json::exception&) {
    // a report that does not read is named below, where its problems are
  }
  if (run.exit_code == kExitOk) {
    r.outcome = CaseOutcome::kPassed;
    return;
  }
  if (run.exit_code == kExitBadInput) {
    r.outcome = CaseOutcome::kError;
    r.message = kBadInputMessage;
    r.details = run.output;
    return;
  }
  const bool judged = run.exit_code == kExitWarn || run.exit_code == kExitCheckFailed;
  std::vector<std::string> problems;
  try {
    if (judged && run.report) problems = Problems(r.family, *run.report);
  } catch (const json::exception& e) {
    problems = {std::string("the report does not read: ") + e.what()};
  }
  if (!judged) {
    r.outcome = CaseOutcome::kError;  // a signal or an unexpected code: the check could not finish
  } else {
    r.outcome = run.exit_code == kExitWarn ? CaseOutcome::kWarned : CaseOutcome::kFailed;
  }
  if (run.signal != 0) {  // hpsf itself died: not the shader's verdict, whatever it printed
    r.message = "hpsf crashed (signal " + std::to_string(run.signal) + ")";
    r.details = run.output;
    return;
  }
  if (run.exit_code == kExitInternalError) {
    r.message = "hpsf failed internally (exit " + std::to_string(kExitInternalError) + ")";
    r.details = run.output;
    return;
  }
  if (problems.empty()) {
    // A kernel fault exits 2 with no report; a crash leaves only what it printed.
    r.message = "exit " + std::to_string(run.exit_code);
    r.details = run.output;
    return;
  }
  r.message = problems.front();
  for (const std::string& line : problems) r.details += line + "\n";
}

}  // namespace hpsf
