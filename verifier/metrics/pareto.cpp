#include "verifier/metrics/pareto.h"

#include <algorithm>
#include <numeric>

namespace hpsf {

std::vector<bool> ParetoFrontier(const std::vector<TimedError>& points) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (points[a].method != points[b].method) return points[a].method < points[b].method;
    if (points[a].seconds != points[b].seconds) return points[a].seconds < points[b].seconds;
    return points[a].error < points[b].error;
  });
  std::vector<bool> frontier(points.size(), false);
  double best = 0.0;  // the smallest error of the method's faster points
  for (std::size_t k = 0; k < order.size(); ++k) {
    const TimedError& p = points[order[k]];
    const bool first = k == 0 || points[order[k - 1]].method != p.method;
    if (first || p.error < best) {
      frontier[order[k]] = true;
      best = p.error;
    }
  }
  return frontier;
}

double FrontierErrorAt(const std::vector<TimedError>& points, const std::vector<bool>& frontier,
                       const std::string& method, double seconds) {
  double error = -1.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!frontier[i] || points[i].method != method || points[i].seconds > seconds) continue;
    if (error < 0.0 || points[i].error < error) error = points[i].error;
  }
  return error;
}

}  // namespace hpsf
