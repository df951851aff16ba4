// The JUnit XML that CI systems read (GitHub Actions' and GitLab's test reports, Jenkins): one <testsuite> per
// gate family, one <testcase> per gate case, a <failure> naming the level and the slot or record that failed, an
// <error> for a case whose check could not finish (a crash), the command that reproduces it in <system-out>. JUnit
// has no warning: a warned case passes there, its warning first in <system-out>.
#ifndef HPSF_VERIFIER_GATE_JUNIT_REPORT_H
#define HPSF_VERIFIER_GATE_JUNIT_REPORT_H

#include <cstddef>
#include <string>
#include <vector>

namespace hpsf {

// Ordered by severity: a report's worst outcome decides the exit code (0, 1, 2, 2).
enum class CaseOutcome { kPassed, kWarned, kFailed, kError };

struct GateCaseResult {
  std::string id;      // "crosscheck/cornell/crowded/vulkan/strict/seed1"
  std::string family;  // "crosscheck", "statistics", "golden" or "fuzz"
  CaseOutcome outcome = CaseOutcome::kPassed;
  double seconds = 0.0;
  std::string message;      // the first failure or warning, one line
  std::string details;      // every failure or warning, or the output of a case that crashed
  std::string reproduce;    // the command line that reproduces the case
  std::string bundle;       // a failed case's repro bundle, else empty
  std::string html;         // the case's own HTML report (a golden's comparisons), else empty
  std::string fixed_point;  // the accumulation and F its report states ("fixed64, F 50"), else empty
  std::size_t index = 0;    // the case's place in the whole gate (a shard runs some of them)
};

std::string JUnitXml(const std::string& name, const std::vector<GateCaseResult>& results);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_JUNIT_REPORT_H
