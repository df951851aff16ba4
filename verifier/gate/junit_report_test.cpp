// The JUnit report CI systems read: each outcome as the element they count.
#include "verifier/gate/junit_report.h"

#include <string>

#include <gtest/gtest.h>

namespace hpsf {
namespace {

// JUnit: a failed case is a <failure>, a case that could not finish (a crash) an <error>, which CI views count as
// not passed; a passed case has neither.
TEST(JUnitXml, ACrashIsAnErrorElementAndAFailureAFailureElement) {
  GateCaseResult crashed, failed, passed;
  crashed.id = "crosscheck/a";
  crashed.family = failed.family = passed.family = "crosscheck";
  crashed.outcome = CaseOutcome::kError;
  crashed.message = "hpsf crashed (signal 11)";
  failed.id = "crosscheck/b";
  failed.outcome = CaseOutcome::kFailed;
  failed.message = "level 2 tables: ...";
  passed.id = "crosscheck/c";
  const std::string xml = JUnitXml("gate", {crashed, failed, passed});
  EXPECT_NE(xml.find("<error message=\"hpsf crashed (signal 11)\" type=\"crash\">"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure message=\"level 2 tables: ...\" type=\"contract\">"), std::string::npos) << xml;
  EXPECT_NE(xml.find("errors=\"1\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("failures=\"1\""), std::string::npos) << xml;
  const std::size_t c = xml.find("name=\"crosscheck/c\"");
  ASSERT_NE(c, std::string::npos);
  const std::string passed_case = xml.substr(c, xml.find("</testcase>", c) - c);
  EXPECT_EQ(passed_case.find("<error"), std::string::npos);
  EXPECT_EQ(passed_case.find("<failure"), std::string::npos);
}

}  // namespace
}  // namespace hpsf
