// What a gate case's command said, as the gate reports it: the outcome from its exit code (0 pass, 1 warn, 2 fail,
// 3 bad input, 4 hpsf's internal error, a signal or anything else a crash) and, from the command's versioned JSON
// report, a first line naming what did not pass (the contract's level and the slot or record for a cross-check or a
// fuzz failure, the rate above its theory for statistics, the backend and the explanation for a golden) and every such
// line in the details.
#ifndef HPSF_VERIFIER_GATE_CASE_JUDGEMENT_H
#define HPSF_VERIFIER_GATE_CASE_JUDGEMENT_H

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "verifier/gate/junit_report.h"

namespace hpsf {

struct CaseRun {
  int exit_code = 0;
  int signal = 0;                        // the signal that ended hpsf, 0 when it exited
  std::string output;                    // what the command printed (its stderr when its report went to a file)
  std::optional<nlohmann::json> report;  // the command's JSON report, when it wrote one that parses
};

// The message of a case whose command refused its input (exit 3): the gate then exits 3 too.
inline constexpr const char* kBadInputMessage = "bad input";

// Sets r.outcome, r.message and r.details for a case of r.family.
void JudgeCase(const CaseRun& run, GateCaseResult& r);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_CASE_JUDGEMENT_H
