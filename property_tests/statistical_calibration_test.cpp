// The false-alarm rate of `hpsf diff --statistical` where it accepts images, measured (tools/calibration) on
// pairs of Cornell box renders that differ only in their seed, so that a change that makes the test cry wolf, or
// go blind to a 5% bias at 16 spp, fails here. Fixed seeds: each count is one outcome that never changes between runs.
//
// Alternative rejected: "two seeds of one render are not consistent with noise" at alpha. Under the test's claim
// the false alarms of P pairs are at most Binomial(P, alpha); each row's bound is the count that distribution
// reaches with probability below 0.002 (over 40 pairs: 4 at alpha 0.01, 11 at 0.1), so a correct test trips it
// with probability at most 0.002 per row. What it catches: the per-pixel z-test (every pair the issue tried at 4
// spp), and Welch's test without the variance floor against a precise image (43% of pairs at 4 against 256 spp).
// 64x64, 4 and 16 spp, each against the same spp and against 256; docs/results.md's table has 200 pairs at 2 to 64 spp.
#include "tools/calibration/statistical_calibration.h"

#include <cstdio>

#include <boost/math/distributions/binomial.hpp>
#include <gtest/gtest.h>

namespace hpsf {
namespace {

// The smallest count k with P(X >= k) < 0.002 for X ~ Binomial(pairs, alpha).
std::uint32_t AlarmBound(std::uint32_t pairs, double alpha) {
  const boost::math::binomial_distribution<> b(pairs, alpha);
  std::uint32_t k = 1;  // P(X >= 0) = 1
  while (k <= pairs && boost::math::cdf(boost::math::complement(b, double(k - 1))) >= 0.002) ++k;
  return k;
}

TEST(StatisticalCalibration, FalseAlarmsStayWithinAlphaAndA5PercentBiasIsSeen) {
  CalibrationPlan plan;
  plan.scenes = {"cornell"};
  plan.spps = {4, 16};
  plan.reference_spp = 256;
  plan.size = 64;
  plan.pairs = 40;
  plan.first_seed = 5001;
  plan.alphas = {0.01, 0.1};
  plan.biases = {0.05};
  const std::vector<CalibrationRow> rows = RunCalibration(plan);
  std::printf("%s", MarkdownTable(plan, rows).c_str());
  ASSERT_EQ(rows.size(), 2u * 4u);  // filtered and not; 4 against 4 and 64, 16 against 16 and 64
  for (const CalibrationRow& row : rows) {
    const std::string what = std::string(row.filtered ? "filtered" : "unfiltered") + ", " + std::to_string(row.spp) +
                             " against " + std::to_string(row.other_spp) + " spp";
    ASSERT_EQ(row.pairs, plan.pairs);
    for (std::size_t k = 0; k < plan.alphas.size(); ++k) {
      EXPECT_LT(row.false_alarms[k], AlarmBound(row.pairs, plan.alphas[k]))
          << what << ": false alarms at alpha " << plan.alphas[k];
    }
    // Power: at 16 spp a 5% bias is caught in 36 to 40 of the 40 pairs (measured with these seeds; 0.90 to 0.94 in
    // docs/results.md's 200 pairs); half of them is a test that lost most of its power.
    if (row.spp == 16) {
      EXPECT_GE(row.detections[0], row.pairs / 2) << what << ": a 5% bias no longer seen";
    }
  }
}

}  // namespace
}  // namespace hpsf
