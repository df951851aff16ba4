#include "tools/hpsf/check_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "tools/hpsf/check_html_report.h"
#include "tools/hpsf/commands.h"
#include "tools/hpsf/html_report.h"
#include "tools/hpsf/subprocess.h"
#include "verifier/gate/case_judgement.h"
#include "verifier/gate/check_report.h"
#include "verifier/gate/gate_file.h"
#include "verifier/gate/gate_schema.h"
#include "verifier/gate/junit_report.h"

namespace hpsf {
namespace {

struct CheckOptions {
  std::string gate_file;
  std::string shard = "1/1";
  std::string junit;
  std::string html;
  std::string out = "hpsf-check";
  bool json = false;
  bool list = false;
  bool schema = false;             // --schema: print the gate file's JSON Schema
  std::vector<std::string> merge;  // --merge: the shards' output directories
};

std::string Quoted(const std::string& word) {
  if (!word.empty() && word.find_first_of(" '\"\\$`*?;&|<>(){}") == std::string::npos) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string CommandLine(const std::vector<std::string>& arguments) {
  std::string line = "hpsf";
  for (const std::string& a : arguments) line += " " + Quoted(a);
  return line;
}

// A case's options through its command's own option layer, options only: a bad one is bad input named with the
// case and its place in the gate file, before any case runs.
void ValidateCase(const Gate& gate, const GateCase& c) {
  CLI::App app;
  CommandContext context;
  context.options_only = true;
  AddCommands(app, context);
  std::vector<const char*> argv = {"hpsf"};
  for (const std::string& a : c.arguments) argv.push_back(a.c_str());
  const std::string where = gate.source + ": case " + c.id + " (" + c.where + "): ";
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    throw InputError(where + e.what());
  } catch (const InputError& e) {
    throw InputError(where + e.what());
  }
}

// The case's file name: its id with '/' as '_'.
std::string FileName(const std::string& id) {
  std::string name = id;
  for (char& c : name) c = c == '/' ? '_' : c;
  return name;
}

// Runs a case's command with what makes its result readable: its JSON report in OUT/reports/NAME.json (crosscheck
// writes it with --report; the others print it with --json, their stdout sent to the file), a failure's repro
// bundle in OUT/bundles/NAME (crosscheck, fuzz), a golden's comparisons in OUT/html/NAME.html.
GateCaseResult RunCase(const GateCase& c, const std::filesystem::path& out) {
  GateCaseResult r;
  r.id = c.id;
  r.family = c.family;
  r.reproduce = CommandLine(c.arguments);
  const std::string name = FileName(c.id);
  const std::filesystem::path report = out / "reports" / (name + ".json");
  const std::filesystem::path bundle = out / "bundles" / name;
  const std::filesystem::path html = out / "html" / (name + ".html");
  std::filesystem::remove(report);
  std::filesystem::remove_all(bundle);  // a bundle left by an earlier gate run in OUT is not this run's
  std::vector<std::string> argv = {SelfPath()};
  argv.insert(argv.end(), c.arguments.begin(), c.arguments.end());
  std::string stdout_file;
  if (c.family == "crosscheck") {
    argv.insert(argv.end(), {"--repro-dir", bundle.string(), "--report", report.string()});
  } else {
    argv.push_back("--json");
    stdout_file = report.string();
  }
  if (c.family == "fuzz") argv.insert(argv.end(), {"--repro-dir", bundle.string()});
  if (c.family == "golden") {
    std::filesystem::create_directories(html.parent_path());
    argv.insert(argv.end(), {"--html", html.string()});
  }
  const auto start = std::chrono::steady_clock::now();
  const ProcessResult process = RunProcess(argv, "", stdout_file);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CaseRun run{process.exit_code, process.signal, process.output, std::nullopt};
  if (std::ifstream in(report); in) {
    nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (!j.is_discarded()) run.report = std::move(j);
  }
  JudgeCase(run, r);
  // A crashed case keeps its bundles too: they are what reproduces the crash.
  const bool failed = r.outcome == CaseOutcome::kFailed || r.outcome == CaseOutcome::kError;
  if (failed && (c.family == "crosscheck" || c.family == "fuzz") && std::filesystem::exists(bundle)) {
    r.bundle = bundle.string();
    r.reproduce = "sh " + (bundle / "reproduce.sh").string();  // the bundle is what a CI job uploads
  }
  if (c.family == "golden" && std::filesystem::exists(html)) r.html = html.string();
  return r;
}

const char* OutcomeWord(CaseOutcome outcome) {
  switch (outcome) {
    case CaseOutcome::kPassed:
      return "PASS";
    case CaseOutcome::kWarned:
      return "WARN";
    case CaseOutcome::kFailed:
      return "FAIL";
    case CaseOutcome::kError:
      break;
  }
  return "ERROR";
}

// The report's outputs: the JUnit file, the HTML page, the JSON report or the summary with its split by family,
// and the command that reproduces each case that did not pass. Exit 3 when a case's options were bad input, else 2
// when a case failed or crashed, else 1 when one warned, else 0.
int Finish(const CheckReport& report, const CheckOptions& o) {
  if (!o.junit.empty()) std::ofstream(o.junit) << JUnitXml("hpsf check " + report.gate, report.results);
  if (!o.html.empty()) WriteHtmlReport(o.html, RenderCheckHtml(report, o.html));
  if (o.json) std::cout << report.ToJson().dump(2) << "\n";
  std::size_t passed = 0;
  for (const GateCaseResult& r : report.results) passed += r.outcome == CaseOutcome::kPassed;
  if (!o.json) {
    for (const FamilyTotals& f : report.Families()) {
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%.1f", f.seconds);
      std::cout << "  " << f.family << ": " << f.passed << " of " << f.cases << " passed"
                << (f.warned ? ", " + std::to_string(f.warned) + " warned" : "")
                << (f.failed ? ", " + std::to_string(f.failed) + " failed" : "")
                << (f.errors ? ", " + std::to_string(f.errors) + " errors" : "") << " (" << seconds << " s)\n";
    }
    std::cout << "check: " << passed << " of " << report.results.size() << " cases passed (" << report.gate
              << ", shard " << report.shard << ")" << std::endl;
  }
  for (const GateCaseResult& r : report.results) {
    if (r.outcome == CaseOutcome::kPassed) continue;
    std::cerr << "hpsf: " << r.id << " reproduces with: " << r.reproduce
              << (r.bundle.empty() ? "" : " (repro bundle: " + r.bundle + ")") << "\n";
  }
  const auto bad_input = [](const GateCaseResult& r) {
    return r.outcome == CaseOutcome::kError && r.message == kBadInputMessage;
  };
  if (std::any_of(report.results.begin(), report.results.end(), bad_input)) {
    return kExitBadInput;
  }
  switch (report.Worst()) {
    case CaseOutcome::kPassed:
      return kExitOk;
    case CaseOutcome::kWarned:
      return kExitWarn;
    default:
      return kExitCheckFailed;
  }
}

// --merge: the reports the shards wrote (DIR/check.json) as one.
int RunMerge(const CheckOptions& o) {
  std::vector<CheckReport> reports;
  std::vector<std::string> sources;
  for (const std::string& dir : o.merge) {
    const std::string source = (std::filesystem::path(dir) / "check.json").string();
    std::ifstream in(source);
    if (!in) throw InputError(source + ": cannot be read (a shard's --out directory holds its check.json)");
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_discarded()) throw InputError(source + ": not valid JSON");
    reports.push_back(CheckReportFromJson(j, source));
    sources.push_back(source);
  }
  return Finish(MergeCheckReports(reports, sources), o);
}

int RunCheck(const CheckOptions& o, bool options_only) {
  if (o.schema) {
    if (!options_only) std::cout << kGateSchemaJson;
    return kExitOk;
  }
  if (!o.merge.empty()) {
    if (!o.gate_file.empty() || o.shard != "1/1" || o.list) {
      throw ConfigError("--merge", "merges the reports of a run's shards: give no gate file, --shard or --list");
    }
    return options_only ? kExitOk : RunMerge(o);
  }
  const auto [index, count] = ParseShard(o.shard);
  if (options_only) return kExitOk;  // the gate is an input: its cases are checked when it is read
  const Gate gate = o.gate_file.empty() ? DefaultGate() : ReadGateFile(o.gate_file);
  const std::vector<GateCase> cases = ShardOf(gate.cases, index, count);
  for (const GateCase& c : cases) ValidateCase(gate, c);
  if (o.list) {
    for (const GateCase& c : cases) std::cout << c.id << "\n";
    return kExitOk;
  }
  const std::filesystem::path out = o.out;
  std::filesystem::create_directories(out / "reports");
  CheckReport report;
  report.gate = gate.source;
  report.shard = o.shard;
  report.gate_cases = gate.cases.size();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    report.results.push_back(RunCase(cases[k], out));
    GateCaseResult& r = report.results.back();
    r.index = (index - 1) + k * count;  // ShardOf's cases I, I + N, ...
    if (!o.json) {
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%.2f", r.seconds);
      std::cout << OutcomeWord(r.outcome) << " " << r.id << " (" << seconds << " s)"
                << (r.message.empty() ? "" : ": " + r.message) << std::endl;
    }
  }
  std::ofstream(out / "check.json") << report.ToJson().dump(2) << "\n";
  return Finish(report, o);
}

}  // namespace

void AddCheckCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* c = app.add_subcommand("check",
                                   "The CI correctness gate: run a gate file's cross-checks, statistics, goldens, "
                                   "fuzzing and captures: exit 0 pass, 1 warn, 2 fail, 3 bad input");
  c->add_option("gate", o->gate_file, "The gate file (JSON, \"hpsf_gate\": 1); none: the default gate");
  c->add_option("--shard", o->shard, "Run shard I of N: cases I, I + N, I + 2N, ...")->capture_default_str();
  c->add_option("--junit", o->junit, "Write the JUnit XML report to FILE");
  c->add_option("--html", o->html, "Write the HTML report, a row per case, to FILE");
  c->add_option("--out", o->out, "Where reports and the failing cases' repro bundles go")->capture_default_str();
  c->add_flag("--json", o->json, "Print the versioned report as JSON");
  c->add_flag("--list", o->list, "List the cases of this shard and exit");
  c->add_flag("--schema", o->schema, "Print the gate file's JSON Schema (for editors and CI linters) and exit");
  c->add_option("--merge", o->merge,
                "Merge the reports of a gate's shards (each DIR a shard's --out, holding its check.json) into one "
                "JUnit, JSON report and summary, as the unsharded run gives")
      ->expected(1, -1);
  c->callback([o, &context] { context.exit_code = RunCheck(*o, context.options_only); });
}

}  // namespace hpsf
