#include "verifier/theory/chi_square.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>

namespace hpsf {
namespace {

constexpr double kMinExpected = 5.0;

}  // namespace

double SidakLevel(double family_alpha, int tests) { return 1.0 - std::pow(1.0 - family_alpha, 1.0 / tests); }

Pooling PoolCells(std::span<const double> probabilities, double samples) {
  Pooling pooling;
  pooling.group_of_cell.assign(probabilities.size(), -1);
  std::vector<std::size_t> cells(probabilities.size());
  std::iota(cells.begin(), cells.end(), 0);
  std::stable_sort(cells.begin(), cells.end(),
                   [&](std::size_t a, std::size_t b) { return probabilities[a] < probabilities[b]; });
  int pool = -1;
  double pooled = 0.0;
  for (std::size_t cell : cells) {
    const double expected = probabilities[cell] * samples;
    if (expected <= 0.0) continue;
    if (expected < kMinExpected || (pool >= 0 && pooled < kMinExpected)) {
      if (pool < 0) pool = pooling.groups++;
      pooling.group_of_cell[cell] = pool;
      pooled += expected;
    } else {
      pooling.group_of_cell[cell] = pooling.groups++;
    }
  }
  return pooling;
}

std::string ChiSquare::ToString() const {
  char text[96];
  std::snprintf(text, sizeof text, "X2 %.1f, dof %d, p %.3g", statistic, dof, p_value);
  return text;
}

ChiSquare ChiSquareTest(std::span<const std::uint64_t> observed, std::span<const double> probabilities) {
  const double samples = double(std::accumulate(observed.begin(), observed.end(), std::uint64_t(0)));
  const Pooling pooling = PoolCells(probabilities, samples);
  std::vector<double> observed_in(pooling.groups), expected_in(pooling.groups);
  ChiSquare result;
  for (std::size_t cell = 0; cell < observed.size(); ++cell) {
    const int group = pooling.group_of_cell[cell];
    if (group < 0 && observed[cell] > 0) {  // an outcome H0 rules out: rejected outright
      result.statistic = std::numeric_limits<double>::infinity();
      result.p_value = 0.0;
    }
    if (group < 0) continue;
    observed_in[group] += double(observed[cell]);
    expected_in[group] += probabilities[cell] * samples;
  }
  result.dof = pooling.groups - 1;
  if (result.p_value == 0.0 || result.dof < 1) return result;
  for (int g = 0; g < pooling.groups; ++g) {
    result.statistic += (observed_in[g] - expected_in[g]) * (observed_in[g] - expected_in[g]) / expected_in[g];
  }
  result.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared(result.dof), result.statistic));
  return result;
}

Power PowerAgainst(std::span<const double> null, std::span<const double> alternative, double samples, double alpha) {
  const Pooling pooling = PoolCells(null, samples);
  std::vector<double> q(pooling.groups), p(pooling.groups);
  double impossible = 0.0;  // the alternative's mass on cells H0 rules out
  for (std::size_t cell = 0; cell < null.size(); ++cell) {
    const int group = pooling.group_of_cell[cell];
    if (group < 0) {
      impossible += alternative[cell];
      continue;
    }
    q[group] += null[cell];
    p[group] += alternative[cell];
  }
  Power result;
  for (int g = 0; g < pooling.groups; ++g) result.noncentrality += samples * (p[g] - q[g]) * (p[g] - q[g]) / q[g];
  const int dof = pooling.groups - 1;
  if (dof >= 1) {
    const double critical = boost::math::quantile(boost::math::complement(boost::math::chi_squared(dof), alpha));
    result.power = boost::math::cdf(
        boost::math::complement(boost::math::non_central_chi_squared(dof, result.noncentrality), critical));
  }
  result.power = std::max(result.power, 1.0 - std::pow(1.0 - impossible, samples));
  return result;
}

}  // namespace hpsf
