#include "tools/hpsf/check_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "tools/gate/gate_file.h"
#include "tools/gate/junit_report.h"
#include "tools/hpsf/crosscheck_command.h"
#include "tools/hpsf/subprocess.h"

namespace hpsf {
namespace {

struct CheckOptions {
  std::string gate_file;
  std::string shard = "1/1";
  std::string junit;
  std::string out = "hpsf-check";
  bool json = false;
  bool list = false;
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

// A case's options through the crosscheck command's own option layer, options only: a bad one is bad input
// named with the case and its place in the gate file, before any case runs.
void ValidateCase(const Gate& gate, const GateCase& c) {
  CLI::App app;
  CommandContext context;
  context.options_only = true;
  AddCrosscheckCommand(app, context);
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

// The case's directory name: its id with '/' as '_'.
std::string FileName(const std::string& id) {
  std::string name = id;
  for (char& c : name) c = c == '/' ? '_' : c;
  return name;
}

GateCaseResult RunCase(const GateCase& c, const std::filesystem::path& out, int& bad_input) {
  GateCaseResult r;
  r.id = c.id;
  r.family = c.family;
  r.reproduce = CommandLine(c.arguments);
  const std::string name = FileName(c.id);
  const std::filesystem::path report = out / "reports" / (name + ".json");
  std::filesystem::remove(report);
  std::vector<std::string> argv = {SelfPath()};
  argv.insert(argv.end(), c.arguments.begin(), c.arguments.end());
  argv.insert(argv.end(), {"--repro-dir", (out / "bundles" / name).string(), "--report", report.string()});
  const auto start = std::chrono::steady_clock::now();
  const ProcessResult process = RunProcess(argv);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (process.exit_code == kExitOk) return r;
  if (process.exit_code == kExitBadInput) {
    ++bad_input;
    r.outcome = CaseOutcome::kError;
    r.message = "bad input";
    r.details = process.output;
    return r;
  }
  if (process.exit_code == kExitCheckFailed && std::filesystem::exists(report)) {
    r.outcome = CaseOutcome::kFailed;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(report));
    for (const nlohmann::json& level : j["levels"]) {
      if (!level["applicable"].get<bool>() || level["passed"].get<bool>()) continue;
      const std::string head =
          "level " + std::to_string(level["level"].get<int>()) + " " + level["name"].get<std::string>();
      for (const nlohmann::json& failure : level["failures"]) {
        if (r.message.empty()) r.message = head + ": " + failure.get<std::string>();
        r.details += head + ": " + failure.get<std::string>() + "\n";
      }
    }
    r.bundle = (out / "bundles" / name).string();
    return r;
  }
  // A kernel fault exits 2 with no report; anything else (a signal, an unexpected code) crashed the check.
  r.outcome = process.exit_code == kExitCheckFailed ? CaseOutcome::kFailed : CaseOutcome::kError;
  r.message = "exit " + std::to_string(process.exit_code);
  r.details = process.output;
  return r;
}

nlohmann::json ToJson(const Gate& gate, const std::string& shard, const std::vector<GateCaseResult>& results) {
  nlohmann::json cases = nlohmann::json::array();
  bool passed = true;
  for (const GateCaseResult& r : results) {
    passed = passed && r.outcome == CaseOutcome::kPassed;
    cases.push_back({{"id", r.id},
                     {"family", r.family},
                     {"outcome", r.outcome == CaseOutcome::kPassed   ? "pass"
                                 : r.outcome == CaseOutcome::kFailed ? "fail"
                                                                     : "error"},
                     {"seconds", r.seconds},
                     {"message", r.message},
                     {"reproduce", r.reproduce},
                     {"bundle", r.bundle}});
  }
  return {{"version", 1},   {"command", "check"}, {"gate", gate.source},
          {"shard", shard}, {"passed", passed},   {"cases", cases}};
}

int RunCheck(const CheckOptions& o, bool options_only) {
  const auto [index, count] = ParseShard(o.shard);
  const Gate gate = o.gate_file.empty() ? DefaultGate() : ReadGateFile(o.gate_file);
  const std::vector<GateCase> cases = ShardOf(gate.cases, index, count);
  for (const GateCase& c : cases) ValidateCase(gate, c);
  if (options_only) return kExitOk;
  if (o.list) {
    for (const GateCase& c : cases) std::cout << c.id << "\n";
    return kExitOk;
  }
  const std::filesystem::path out = o.out;
  std::filesystem::create_directories(out / "reports");
  std::vector<GateCaseResult> results;
  int bad_input = 0;
  for (const GateCase& c : cases) {
    results.push_back(RunCase(c, out, bad_input));
    const GateCaseResult& r = results.back();
    if (!o.json) {
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%.2f", r.seconds);
      std::cout << (r.outcome == CaseOutcome::kPassed   ? "PASS "
                    : r.outcome == CaseOutcome::kFailed ? "FAIL "
                                                        : "ERROR ")
                << r.id << " (" << seconds << " s)" << (r.message.empty() ? "" : ": " + r.message) << std::endl;
    }
  }
  if (!o.junit.empty()) std::ofstream(o.junit) << JUnitXml("hpsf check " + gate.source, results);
  const nlohmann::json report = ToJson(gate, o.shard, results);
  if (o.json) std::cout << report.dump(2) << "\n";
  std::size_t failed = 0;
  for (const GateCaseResult& r : results) failed += r.outcome != CaseOutcome::kPassed;
  if (!o.json) {
    std::cout << "check: " << results.size() - failed << " of " << results.size() << " cases passed (" << gate.source
              << ", shard " << o.shard << ")" << std::endl;
  }
  for (const GateCaseResult& r : results) {
    if (r.outcome == CaseOutcome::kPassed) continue;
    std::cerr << "hpsf: " << r.id << " reproduces with: " << r.reproduce
              << (r.bundle.empty() ? "" : " (repro bundle: " + r.bundle + ")") << "\n";
  }
  if (bad_input > 0) return kExitBadInput;
  return failed > 0 ? kExitCheckFailed : kExitOk;
}

}  // namespace

void AddCheckCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* c = app.add_subcommand("check", "The CI correctness gate: run a gate file's matrix of cross-checks");
  c->add_option("gate", o->gate_file, "The gate file (JSON, \"hpsf_gate\": 1); none: the default gate");
  c->add_option("--shard", o->shard, "Run shard I of N: cases I, I + N, I + 2N, ...")->capture_default_str();
  c->add_option("--junit", o->junit, "Write the JUnit XML report to FILE");
  c->add_option("--out", o->out, "Where reports and the failing cases' repro bundles go")->capture_default_str();
  c->add_flag("--json", o->json, "Print the versioned report as JSON");
  c->add_flag("--list", o->list, "List the cases of this shard and exit");
  c->callback([o, &context] { context.exit_code = RunCheck(*o, context.options_only); });
}

}  // namespace hpsf
