// The jitter's distributions (Binder et al. §3.1), read from the cells a key pass returns: any key pass, core's
// or a device's, can be judged, since each test places records so that the cell reveals the jitter. Each test is
// a Pearson chi-square (verifier/theory/chi_square) against the exact law of a correct jitter:
//   square   (2u1 - 1, 2u2 - 1) uniform on the square: 16 x 16 cells of the offset, so both uniform and
//            independent of each other;
//   mean     both components of zero mean (the sum of the two squared z-scores, chi-square with 2 dof);
//   pixels / samples / bounces: the jitter of a record and of the one with the next pixel (sample, bounce)
//            independent: 4 x 4 x 4 x 4 cells of the two offsets;
//   kernel   the effective kernel: a point uniform in its cell lands in the neighbouring cell (dx, dy) as often
//            as the box-box convolution says (1/4, 1/2, 1/4 per axis at jitter 1);
//   level    with level of detail, the level change l' - l at grazing incidence equals the one predicted from
//            each record's distance to its level's boundaries.
// `hpsf stats` runs them on a user's seed and frame.
#ifndef HPSF_VERIFIER_THEORY_JITTER_STATISTICS_H
#define HPSF_VERIFIER_THEORY_JITTER_STATISTICS_H

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/key_batch.h"
#include "core/record.h"
#include "verifier/theory/chi_square.h"

namespace hpsf {

using KeyPassFunction = std::function<std::vector<KeyResult>(std::span<const Record>, const KeyParams&)>;
std::vector<KeyResult> CoreKeyPass(std::span<const Record> records, const KeyParams& params);

enum class JitterTest { kSquare, kMean, kPixelPairs, kSamplePairs, kBouncePairs, kKernel, kLevelChange };
inline constexpr JitterTest kJitterTests[] = {
    JitterTest::kSquare,      JitterTest::kMean,   JitterTest::kPixelPairs, JitterTest::kSamplePairs,
    JitterTest::kBouncePairs, JitterTest::kKernel, JitterTest::kLevelChange};
const char* ToString(JitterTest test);

// A test's batch and the parameters it runs under: change either to plant an alternative.
struct JitterExperiment {
  JitterTest test;
  std::vector<Record> records;
  KeyParams params;
  std::vector<double> probabilities;  // per cell, under H0 (for the level test, the mean over the records)
};
// `samples` records (pairs for the pair tests); the counter RNG runs on `seed` and `frame`.
JitterExperiment MakeJitterExperiment(JitterTest test, std::uint32_t seed, std::uint32_t frame, std::uint32_t samples);

// The counts per cell of the keys the pass returned for the experiment's records.
std::vector<std::uint64_t> CountJitterCells(const JitterExperiment& experiment, std::span<const KeyResult> keys);

struct JitterVerdict {
  JitterTest test;
  std::uint64_t samples = 0;
  ChiSquare chi_square;
};
JitterVerdict RunJitterTest(const KeyPassFunction& pass, const JitterExperiment& experiment);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_THEORY_JITTER_STATISTICS_H
