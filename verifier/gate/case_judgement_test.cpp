// JudgeCase on what a case's command left: a verdict (exit 0, 1, 2) read from its report, bad input (3), and hpsf's
// own failures told apart from a shader's verdict: an escaped exception (exit 4) and a signal.
#include "verifier/gate/case_judgement.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace hpsf {
namespace {

GateCaseResult Judged(const CaseRun& run, const std::string& family = "crosscheck") {
  GateCaseResult r;
  r.family = family;
  JudgeCase(run, r);
  return r;
}

nlohmann::json FailedCrosscheck() {
  return {{"accumulation", "fixed64"},
          {"fixed_point_bits", 50},
          {"levels",
           {{{"level", 2},
             {"name", "tables"},
             {"applicable", true},
             {"passed", false},
             {"failures", {"vulkan: invalid shader output: record 3: placement 9 is neither a slot"}}}}}};
}

TEST(CaseJudgement, FailedCheckNamesItsLevel) {
  const GateCaseResult r = Judged({2, 0, "", FailedCrosscheck()});
  EXPECT_EQ(r.outcome, CaseOutcome::kFailed);
  EXPECT_EQ(r.message, "level 2 tables: vulkan: invalid shader output: record 3: placement 9 is neither a slot");
  EXPECT_EQ(r.fixed_point, "fixed64, F 50");
}

// A golden check's report lists every comparison; the message is the first one that did not pass, in the words
// `hpsf golden check` writes its verdicts in.
TEST(CaseJudgement, GoldenFailureNamesTheComparisonThatFailedNotOneThatPassed) {
  const nlohmann::json check = {{"checks",
                                 {{{"case", "cornell"},
                                   {"backend", "reference"},
                                   {"verdict", "PASS"},
                                   {"explanation", "PASS: max 0 <= 0"},
                                   {"artifacts", nlohmann::json::array()}},
                                  {{"case", "cornell"},
                                   {"backend", "vulkan"},
                                   {"verdict", "FAIL"},
                                   {"explanation", "FAIL: max 0.5 > 0"},
                                   {"artifacts", {"heat.png"}}}}}};
  const GateCaseResult r = Judged({2, 0, "", check}, "golden");
  EXPECT_EQ(r.outcome, CaseOutcome::kFailed);
  EXPECT_EQ(r.message, "cornell on vulkan: FAIL: max 0.5 > 0");
  EXPECT_EQ(r.details.find("on reference"), std::string::npos) << r.details;
}

TEST(CaseJudgement, StatesTheAccumulationAndFOfItsReport) {
  EXPECT_EQ(Judged({0, 0, "", nlohmann::json{{"accumulation", "float32"}, {"fixed_point_bits", 40}}}).fixed_point,
            "float32");
  const nlohmann::json fuzz = {{"fixed_point_bits", {{"min", -2}, {"max", 62}}}};
  EXPECT_EQ(Judged({0, 0, "", fuzz}, "fuzz").fixed_point, "fixed64 at F -2 to 62");
  EXPECT_EQ(Judged({0, 0, "", nlohmann::json{{"fixed_point_bits", nullptr}}}, "fuzz").fixed_point, "");
}

TEST(CaseJudgement, SignalIsACrashOfHpsfWhateverItPrinted) {
  const GateCaseResult r = Judged({134, 6, "free(): invalid pointer\n", FailedCrosscheck()});
  EXPECT_EQ(r.outcome, CaseOutcome::kError);
  EXPECT_EQ(r.message, "hpsf crashed (signal 6)");
  EXPECT_EQ(r.details, "free(): invalid pointer\n");
}

TEST(CaseJudgement, EscapedExceptionIsAnInternalError) {
  const GateCaseResult r = Judged({kExitInternalError, 0, "hpsf: internal error (exit 4): bad_alloc\n", std::nullopt});
  EXPECT_EQ(r.outcome, CaseOutcome::kError);
  EXPECT_EQ(r.message, "hpsf failed internally (exit 4)");
}

TEST(CaseJudgement, BadInputAndPass) {
  EXPECT_EQ(Judged({3, 0, "hpsf: --capacity: ...", std::nullopt}).message, kBadInputMessage);
  EXPECT_EQ(Judged({0, 0, "", std::nullopt}).outcome, CaseOutcome::kPassed);
}

}  // namespace
}  // namespace hpsf
