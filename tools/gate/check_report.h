// The report of one `hpsf check` run (issue 16), written as OUT/check.json by every run and printed by --json, and
// the merge of the reports of a gate's shards (`hpsf check --merge DIR...`): each case carries its index in the whole
// gate, so shards 1..N of one gate merge into the report the unsharded run writes, case for case in gate order
// (times and bundle paths are the runs' own).
#ifndef HPSF_TOOLS_GATE_CHECK_REPORT_H
#define HPSF_TOOLS_GATE_CHECK_REPORT_H

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/gate/junit_report.h"

namespace hpsf {

struct CheckReport {
  std::string gate;            // the gate file, or "the default gate"
  std::string shard = "1/1";   // "I/N", or "1/1" for a merge of every shard
  std::size_t gate_cases = 0;  // cases in the whole gate
  std::vector<GateCaseResult> results;  // this run's, in gate order, each with its index

  bool Passed() const;
  nlohmann::json ToJson() const;  // version 1
};

// A report read back; an InputError naming `source` and the JSON place of what is wrong.
CheckReport CheckReportFromJson(const nlohmann::json& j, const std::string& source);

// The shards' reports as one: the same gate and gate size in every one, each case index once, every index of the
// gate present; an InputError naming the report (its `sources` entry) otherwise.
CheckReport MergeCheckReports(const std::vector<CheckReport>& reports, const std::vector<std::string>& sources);

}  // namespace hpsf

#endif  // HPSF_TOOLS_GATE_CHECK_REPORT_H
