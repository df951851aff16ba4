// The report of one `hpsf check` run, written as OUT/check.json by every run and printed by --json, and
// the merge of the reports of a gate's shards (`hpsf check --merge DIR...`): each case carries its index in the whole
// gate, so shards 1..N of one gate merge into the report the unsharded run writes, case for case in gate order
// (times and bundle paths are the runs' own).
#ifndef HPSF_VERIFIER_GATE_CHECK_REPORT_H
#define HPSF_VERIFIER_GATE_CHECK_REPORT_H

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "verifier/gate/junit_report.h"

namespace hpsf {

// One family's share of a run: its cases by outcome and the seconds they took (the gate's wall time by family).
struct FamilyTotals {
  std::string family;
  std::size_t cases = 0, passed = 0, warned = 0, failed = 0, errors = 0;
  double seconds = 0.0;
};

struct CheckReport {
  std::string gate;                     // the gate file, or "the default gate"
  std::string shard = "1/1";            // "I/N", or "1/1" for a merge of every shard
  std::size_t gate_cases = 0;           // cases in the whole gate
  std::vector<GateCaseResult> results;  // this run's, in gate order, each with its index

  CaseOutcome Worst() const;                                       // kPassed when there is no case
  bool Passed() const { return Worst() <= CaseOutcome::kWarned; }  // no case failed or crashed
  std::vector<FamilyTotals> Families() const;                      // in the order families first appear in the results
  nlohmann::json ToJson() const;                                   // version 1
};

// A report read back; an InputError naming `source` and the JSON place of what is wrong.
CheckReport CheckReportFromJson(const nlohmann::json& j, const std::string& source);

// The shards' reports as one: the same gate and gate size in every one, each case index once, every index of the
// gate present; an InputError naming the report (its `sources` entry) otherwise.
CheckReport MergeCheckReports(const std::vector<CheckReport>& reports, const std::vector<std::string>& sources);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_CHECK_REPORT_H
