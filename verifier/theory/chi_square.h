// Pearson's chi-square goodness-of-fit test as docs/design/testing.md asks for it (Mitsuba 3, pbrt-v4): cells whose
// expected count is below 5 pooled, the p-value and the power against a named alternative from Boost.Math.
// Shared by the statistics tests and `hpsf stats`.
#ifndef HPSF_VERIFIER_THEORY_CHI_SQUARE_H
#define HPSF_VERIFIER_THEORY_CHI_SQUARE_H

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace hpsf {

// The per-test level that holds a family of `tests` independent tests at `family_alpha`.
double SidakLevel(double family_alpha, int tests);

// Cell -> group. Cells expected to hold 5 or more stand alone; smaller ones are pooled in ascending order of
// probability, and the pool takes further cells until it reaches 5. -1 marks a cell H0 gives probability 0.
struct Pooling {
  std::vector<int> group_of_cell;
  int groups = 0;
};
Pooling PoolCells(std::span<const double> probabilities, double samples);

struct ChiSquare {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 1.0;
  std::string ToString() const;
};

// H0: the counts are multinomial with these cell probabilities (summing to 1). An outcome H0 gives probability
// 0 rejects outright (p = 0).
ChiSquare ChiSquareTest(std::span<const std::uint64_t> observed, std::span<const double> probabilities);

// The probability that the test at `alpha` rejects an alternative with these cell probabilities after `samples`
// draws: the statistic is asymptotically noncentral chi-square with noncentrality N sum (p - q)^2 / q over the
// same pooled cells.
struct Power {
  double noncentrality = 0.0;
  double power = 0.0;
};
Power PowerAgainst(std::span<const double> null, std::span<const double> alternative, double samples, double alpha);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_THEORY_CHI_SQUARE_H
