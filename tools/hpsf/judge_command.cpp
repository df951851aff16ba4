#include "tools/hpsf/judge_command.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "core/capture_file.h"
#include "core/error.h"
#include "tools/hpsf/seconds_since.h"
#include "verifier/contract/capture_judgement.h"
#include "verifier/gate/junit_report.h"
#include "verifier/gate/table_declaration.h"

namespace hpsf {
namespace {

struct JudgeOptions {
  std::vector<std::string> captures;
  std::vector<std::string> reruns;  // --rerun: the same frames from another run, paired with the captures in order
  bool json = false;
  std::string junit_file;
};

struct JudgedCapture {
  std::string path;
  std::string rerun;  // the capture judged against for level 4, or ""
  CrosscheckReport report;
  double seconds = 0.0;
};

// A directory stands for the captures in it, in name order.
std::vector<std::string> CaptureFiles(const std::vector<std::string>& given) {
  std::vector<std::string> files;
  for (const std::string& path : given) {
    if (!std::filesystem::is_directory(path)) {
      files.push_back(path);
      continue;
    }
    std::vector<std::string> inside;
    for (const auto& entry : std::filesystem::directory_iterator(path)) {
      if (entry.is_regular_file() && entry.path().extension() == ".hpsfc") inside.push_back(entry.path().string());
    }
    if (inside.empty()) throw InputError(path + ": a directory without captures (*.hpsfc)");
    std::sort(inside.begin(), inside.end());
    files.insert(files.end(), inside.begin(), inside.end());
  }
  return files;
}

JudgedCapture Judge(const std::string& path, const std::string& rerun_path) {
  const auto start = std::chrono::steady_clock::now();
  const Capture capture = ReadCapture(path);
  std::optional<Capture> rerun;
  if (!rerun_path.empty()) rerun = ReadCapture(rerun_path);
  FilterConfig config;
  ApplyTableDeclarationText(capture.declaration, path + ": its declaration", config);
  JudgedCapture judged{path, rerun_path, JudgeCapture(capture, config, rerun ? &*rerun : nullptr), 0.0};
  judged.seconds = SecondsSince(start);
  return judged;
}

GateCaseResult JUnitCase(const JudgedCapture& j, std::size_t index) {
  GateCaseResult r;
  // The capture's folder then its name: CI systems group a folder's frames (classname, verifier/gate/junit_report.h).
  const std::filesystem::path path(j.path);
  const std::string folder = path.parent_path().filename().string();
  r.id = "judge/" + (folder.empty() ? "." : folder) + "/" + path.filename().string();
  r.family = "judge";
  r.outcome = j.report.Passed() ? CaseOutcome::kPassed : CaseOutcome::kFailed;
  r.seconds = j.seconds;
  r.message = j.report.FirstFailure();
  r.details = j.report.ToText();
  r.reproduce = "hpsf judge " + j.path + (j.rerun.empty() ? "" : " --rerun " + j.rerun);
  r.fixed_point = ToString(j.report.accumulation) + ", F " + std::to_string(j.report.fixed_point_bits);
  r.index = index;
  return r;
}

int Run(const JudgeOptions& o, bool options_only) {
  if (options_only) return kExitOk;
  // Every capture is read and judged before anything is printed: a bad one leaves no partial output.
  const std::vector<std::string> files = CaptureFiles(o.captures);
  const std::vector<std::string> reruns = o.reruns.empty() ? std::vector<std::string>{} : CaptureFiles(o.reruns);
  if (!reruns.empty() && reruns.size() != files.size()) {
    throw ConfigError("--rerun", "names " + std::to_string(reruns.size()) + " captures for the " +
                                     std::to_string(files.size()) + " judged: give one rerun of each, in their order");
  }
  std::vector<JudgedCapture> judged;
  for (std::size_t i = 0; i < files.size(); ++i) judged.push_back(Judge(files[i], reruns.empty() ? "" : reruns[i]));
  bool passed = true;
  nlohmann::json json = {{"version", 1}, {"captures", nlohmann::json::array()}};
  std::vector<GateCaseResult> cases;
  for (const JudgedCapture& j : judged) {
    passed = passed && j.report.Passed();
    json["captures"].push_back({{"capture", j.path}, {"rerun", j.rerun}, {"report", j.report.ToJson()}});
    cases.push_back(JUnitCase(j, cases.size()));
    if (!o.json) std::cout << j.path << ": " << (j.report.Passed() ? "PASS" : "FAIL") << "\n" << j.report.ToText();
  }
  json["passed"] = passed;
  if (o.json) std::cout << json.dump(2) << "\n";
  if (!o.junit_file.empty()) {
    std::ofstream out(o.junit_file);
    out << JUnitXml("hpsf judge", cases);
    if (!out) throw InputError(o.junit_file + ": cannot write the JUnit report");
  }
  return passed ? kExitOk : kExitCheckFailed;
}

}  // namespace

void AddJudgeCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<JudgeOptions>();
  CLI::App* c = app.add_subcommand(
      "judge", "Judge frames captured from a team's engine (FILE.hpsfc, or a directory of them) by the contract");
  c->add_option("captures", o->captures, "Captures, or directories of captures (*.hpsfc)")->required();
  c->add_option("--rerun", o->reruns,
                "The same frames captured from another run of the same inputs (files or directories, paired with the "
                "captures in order): level 4 judges what the rerun must repeat");
  c->add_flag("--json", o->json, "Print the versioned verdicts as JSON");
  c->add_option("--junit", o->junit_file, "Also write a JUnit XML report to FILE, one test case per capture");
  c->callback([o, &context] { context.exit_code = Run(*o, context.options_only); });
}

}  // namespace hpsf
