#include "verifier/gate/check_report.h"

#include <algorithm>
#include <iterator>

#include "core/error.h"

namespace hpsf {
namespace {

constexpr const char* kOutcomeNames[] = {"pass", "warn", "fail", "error"};

const char* OutcomeName(CaseOutcome outcome) { return kOutcomeNames[int(outcome)]; }

// The value at `pointer` in `j`, of the wanted kind; an InputError naming the source and the place otherwise.
const nlohmann::json& At(const nlohmann::json& j, const std::string& pointer, nlohmann::json::value_t kind,
                         const std::string& source) {
  const nlohmann::json::json_pointer p(pointer);
  if (!j.contains(p)) throw InputError(source + ": " + pointer + ": missing");
  const nlohmann::json& v = j.at(p);
  const bool number = kind == nlohmann::json::value_t::number_unsigned && v.is_number_unsigned();
  const bool real = kind == nlohmann::json::value_t::number_float && v.is_number();
  if (v.type() != kind && !number && !real)
    throw InputError(source + ": " + pointer + ": not a " +
                     std::string(kind == nlohmann::json::value_t::string  ? "string"
                                 : kind == nlohmann::json::value_t::array ? "list"
                                                                          : "number"));
  return v;
}

}  // namespace

CaseOutcome CheckReport::Worst() const {
  CaseOutcome worst = CaseOutcome::kPassed;
  for (const GateCaseResult& r : results) worst = std::max(worst, r.outcome);
  return worst;
}

std::vector<FamilyTotals> CheckReport::Families() const {
  std::vector<FamilyTotals> families;
  for (const GateCaseResult& r : results) {
    auto it =
        std::find_if(families.begin(), families.end(), [&](const FamilyTotals& f) { return f.family == r.family; });
    if (it == families.end()) it = families.insert(families.end(), FamilyTotals{r.family});
    ++it->cases;
    it->passed += r.outcome == CaseOutcome::kPassed;
    it->warned += r.outcome == CaseOutcome::kWarned;
    it->failed += r.outcome == CaseOutcome::kFailed;
    it->errors += r.outcome == CaseOutcome::kError;
    it->seconds += r.seconds;
  }
  return families;
}

nlohmann::json CheckReport::ToJson() const {
  nlohmann::json cases = nlohmann::json::array();
  for (const GateCaseResult& r : results) {
    cases.push_back({{"index", r.index},
                     {"id", r.id},
                     {"family", r.family},
                     {"outcome", OutcomeName(r.outcome)},
                     {"seconds", r.seconds},
                     {"message", r.message},
                     {"details", r.details},
                     {"reproduce", r.reproduce},
                     {"bundle", r.bundle},
                     {"html", r.html},
                     {"fixed_point", r.fixed_point}});
  }
  nlohmann::json families = nlohmann::json::object();
  for (const FamilyTotals& f : Families()) {
    families[f.family] = {{"cases", f.cases}, {"pass", f.passed},  {"warn", f.warned},
                          {"fail", f.failed}, {"error", f.errors}, {"seconds", f.seconds}};
  }
  return {{"version", 1},
          {"command", "check"},
          {"gate", gate},
          {"shard", shard},
          {"gate_cases", gate_cases},
          {"passed", Passed()},
          {"outcome", OutcomeName(Worst())},
          {"families", families},
          {"cases", cases}};
}

CheckReport CheckReportFromJson(const nlohmann::json& j, const std::string& source) {
  using Kind = nlohmann::json::value_t;
  if (!j.is_object()) throw InputError(source + ": not a JSON object");
  if (At(j, "/version", Kind::number_unsigned, source).get<int>() != 1)
    throw InputError(source + ": /version: expected 1");
  if (At(j, "/command", Kind::string, source).get<std::string>() != "check") {
    throw InputError(source + ": /command: not a report of hpsf check");
  }
  CheckReport report;
  report.gate = At(j, "/gate", Kind::string, source).get<std::string>();
  report.shard = At(j, "/shard", Kind::string, source).get<std::string>();
  report.gate_cases = At(j, "/gate_cases", Kind::number_unsigned, source).get<std::size_t>();
  const nlohmann::json& cases = At(j, "/cases", Kind::array, source);
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::string at = "/cases/" + std::to_string(k);
    GateCaseResult r;
    r.index = At(j, at + "/index", Kind::number_unsigned, source).get<std::size_t>();
    r.id = At(j, at + "/id", Kind::string, source).get<std::string>();
    r.family = At(j, at + "/family", Kind::string, source).get<std::string>();
    const std::string outcome = At(j, at + "/outcome", Kind::string, source).get<std::string>();
    const auto name = std::find(std::begin(kOutcomeNames), std::end(kOutcomeNames), outcome);
    if (name == std::end(kOutcomeNames)) {
      throw InputError(source + ": " + at + "/outcome: expected pass, warn, fail or error; got '" + outcome + "'");
    }
    r.outcome = CaseOutcome(name - std::begin(kOutcomeNames));
    r.seconds = At(j, at + "/seconds", Kind::number_float, source).get<double>();
    r.message = At(j, at + "/message", Kind::string, source).get<std::string>();
    r.details = At(j, at + "/details", Kind::string, source).get<std::string>();
    r.reproduce = At(j, at + "/reproduce", Kind::string, source).get<std::string>();
    r.bundle = At(j, at + "/bundle", Kind::string, source).get<std::string>();
    r.html = At(j, at + "/html", Kind::string, source).get<std::string>();
    r.fixed_point = At(j, at + "/fixed_point", Kind::string, source).get<std::string>();
    if (r.index >= report.gate_cases) {
      throw InputError(source + ": " + at + "/index: " + std::to_string(r.index) + " is not below /gate_cases " +
                       std::to_string(report.gate_cases));
    }
    report.results.push_back(std::move(r));
  }
  return report;
}

CheckReport MergeCheckReports(const std::vector<CheckReport>& reports, const std::vector<std::string>& sources) {
  if (reports.empty()) throw InputError("--merge: no reports");
  CheckReport merged;
  merged.gate = reports[0].gate;
  merged.gate_cases = reports[0].gate_cases;
  std::vector<const GateCaseResult*> by_index(merged.gate_cases, nullptr);
  std::vector<std::size_t> from(merged.gate_cases, 0);
  for (std::size_t k = 0; k < reports.size(); ++k) {
    const CheckReport& r = reports[k];
    if (r.gate != merged.gate || r.gate_cases != merged.gate_cases) {
      throw InputError(sources[k] + ": a report of " + r.gate + " (" + std::to_string(r.gate_cases) +
                       " cases), not of " + merged.gate + " (" + std::to_string(merged.gate_cases) + " cases) as " +
                       sources[0]);
    }
    for (const GateCaseResult& c : r.results) {
      if (by_index[c.index]) {
        throw InputError(sources[k] + ": case " + c.id + " is in " + sources[from[c.index]] + " too");
      }
      by_index[c.index] = &c;
      from[c.index] = k;
    }
  }
  for (std::size_t i = 0; i < by_index.size(); ++i) {
    if (!by_index[i]) {
      throw InputError("--merge: case " + std::to_string(i) + " of " + merged.gate +
                       " is in none of the reports: a shard is missing");
    }
    merged.results.push_back(*by_index[i]);
  }
  return merged;
}

}  // namespace hpsf
