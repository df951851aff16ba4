// The Pareto frontier (verifier/metrics/pareto.h) on constructed points: per method, only points that beat every
// faster one; ties in time to the smaller error; the frontier's error at a time budget.
#include "verifier/metrics/pareto.h"

#include <gtest/gtest.h>

namespace hpsf {
namespace {

TEST(Pareto, EachMethodKeepsThePointsNoFasterOneBeats) {
  const std::vector<TimedError> points = {
      {"pt", 1.0, 0.5},    // 0: frontier
      {"pt", 2.0, 0.3},    // 1: frontier
      {"pt", 3.0, 0.4},    // 2: slower and worse than 1
      {"hpsf", 1.5, 0.2},  // 3: frontier (another method)
      {"hpsf", 1.5, 0.1},  // 4: frontier; same time as 3, smaller error, so 3 is not
      {"pt", 4.0, 0.3},    // 5: equal error to 1, slower
      {"pt", 5.0, 0.1},    // 6: frontier
  };
  EXPECT_EQ(ParetoFrontier(points), (std::vector<bool>{true, true, false, false, true, false, true}));
}

TEST(Pareto, TheFrontierAtATimeBudget) {
  const std::vector<TimedError> points = {{"pt", 1.0, 0.5}, {"pt", 2.0, 0.3}, {"hpsf", 1.5, 0.1}};
  const std::vector<bool> frontier = ParetoFrontier(points);
  EXPECT_EQ(FrontierErrorAt(points, frontier, "pt", 1.9), 0.5);
  EXPECT_EQ(FrontierErrorAt(points, frontier, "pt", 2.0), 0.3);
  EXPECT_EQ(FrontierErrorAt(points, frontier, "hpsf", 1.0), -1.0);
  EXPECT_EQ(FrontierErrorAt(points, frontier, "radius", 9.0), -1.0);
}

}  // namespace
}  // namespace hpsf
