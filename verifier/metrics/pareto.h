// The Pareto frontier of accuracy against time: among a method's configurations, those that no faster
// (or equally fast) configuration of the same method beats or equals in error. Plain path tracing's frontier is the
// line the filters must get under at equal time.
#ifndef HPSF_VERIFIER_METRICS_PARETO_H
#define HPSF_VERIFIER_METRICS_PARETO_H

#include <string>
#include <vector>

namespace hpsf {

struct TimedError {
  std::string method;
  double seconds = 0.0;
  double error = 0.0;
};

// frontier[i]: whether point i is on its method's frontier. Ties in time go to the smaller error, then to the
// earlier point; a point equal in both to an earlier one is not on the frontier.
std::vector<bool> ParetoFrontier(const std::vector<TimedError>& points);

// The error of `method`'s frontier at `seconds`: that of its fastest-or-equal frontier point that takes no more than
// `seconds` (the best it reaches in that time), or a negative value when none is that fast.
double FrontierErrorAt(const std::vector<TimedError>& points, const std::vector<bool>& frontier,
                       const std::string& method, double seconds);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_METRICS_PARETO_H
