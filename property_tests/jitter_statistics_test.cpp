// Jitter: the statistics the filter's quality rests on (Binder et al. §3.1), from core's key path and from
// Vulkan's keys (verifier/theory/jitter_statistics reads the jitter back from the cells). H0 for each: the law of a
// correct jitter. Pearson chi-square (pooled cells), Sidak over the 7 tests x 2 key passes, family at 0.001;
// fixed seeds, so no verdict changes between runs. Alternatives, each rejected by the same statistic on the
// same records, with its power computed from its exact cell probabilities (noncentral chi-square):
//   square  jitter along the tangent only (u2 unused; D4's kind of frame error) and an amplitude 10% off;
//   mean    a jitter 4% short on its negative side;
//   pairs   a counter RNG that drops the pixel, the sample or the bounce (neighbours jitter alike);
//   kernel  an amplitude 10% off and jitter along the tangent only;
//   level   the level not recomputed after the jitter (D5).
// And, from core, the jittered offset stays in the tangent plane to the bound its float rounding allows; D4's
// projection d - |n| d leaves it.
#include "verifier/theory/jitter_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <utility>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <gtest/gtest.h>

#include "core/shared/jitter.h"
#include "core/shared/rng.h"
#include "property_tests/vulkan_test_devices.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kSeed = 20261123;
constexpr std::uint32_t kSamples = 1u << 16;
constexpr std::uint32_t kMeanSamples = 1u << 18;  // the mean test's power needs more
const double kAlpha = SidakLevel(0.001, 2 * int(std::size(kJitterTests)));
constexpr double kMinPower = 0.999;

std::uint32_t Samples(JitterTest test) { return test == JitterTest::kMean ? kMeanSamples : kSamples; }

KeyPassFunction VulkanKeyPass() {
  return [](std::span<const Record> records, const KeyParams& params) {
    return TestKeyPass(StagingPolicy::kAuto).Run(records, params);
  };
}

TEST(JitterStatistics, CoreAndVulkanKeysHoldEveryLaw) {
  for (const auto& [name, pass] : {std::pair<const char*, KeyPassFunction>{"core", CoreKeyPass},
                                   std::pair<const char*, KeyPassFunction>{"vulkan", VulkanKeyPass()}}) {
    for (const JitterTest test : kJitterTests) {
      const JitterVerdict v = RunJitterTest(pass, MakeJitterExperiment(test, kSeed, 0, Samples(test)));
      std::printf("%-6s %-13s %llu samples: %s\n", name, ToString(test), (unsigned long long)v.samples,
                  v.chi_square.ToString().c_str());
      EXPECT_GT(v.chi_square.p_value, kAlpha) << name << ", " << ToString(test) << ": " << v.chi_square.ToString();
    }
  }
}

// --- Alternatives ---

struct Alternative {
  const char* name;
  JitterTest test;
  std::function<void(JitterExperiment&)> plant;                         // on the records or parameters
  std::function<std::vector<KeyResult>(std::vector<KeyResult>)> alter;  // or on the keys the pass returns
  std::vector<double> probabilities;                                    // its exact cell probabilities
};

// Per axis of the 7-bit offset reading (16 bins of 8 cells and the outside), with the amplitude scaled by `a`.
std::vector<double> ScaledOffsetBins(double a) {
  std::vector<double> p(17, 0.0);
  for (int bin = 0; bin < 16; ++bin) {
    const double low = -1.0 + bin / 8.0, high = low + 1.0 / 8.0;  // the bin in units of the amplitude
    p[bin] = std::max(0.0, std::min(high, a) - std::max(low, -a)) / (2.0 * a);
  }
  p[16] = std::max(0.0, 1.0 - std::accumulate(p.begin(), p.begin() + 16, 0.0));
  return p;
}

std::vector<double> Square(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> p(16 * 16 + 1, 0.0);
  for (int i = 0; i < 17; ++i) {
    for (int j = 0; j < 17; ++j) p[i < 16 && j < 16 ? i * 16 + j : 256] += x[i] * y[j];
  }
  return p;
}

std::vector<double> AtBinEight() {  // u2 unused: the bitangent offset is always 0, bin 8
  std::vector<double> p(17, 0.0);
  p[8] = 1.0;
  return p;
}

// The kernel per axis at amplitude a, for points stratified over the unit cell: cells -2..2 (the outer two are
// outside the null's cells).
std::vector<double> KernelAxis(double a) {
  std::vector<double> p(5, 0.0);
  constexpr int kStrata = 256;
  for (int s = 0; s < kStrata; ++s) {
    const double f = (s + 0.5) / kStrata;
    for (int k = -2; k <= 2; ++k) {
      p[k + 2] += std::max(0.0, std::min(k + 1.0, f + a) - std::max(double(k), f - a)) / (2.0 * a) / kStrata;
    }
  }
  return p;
}

std::vector<double> Kernel(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> p(10, 0.0);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      const bool inside = i >= 1 && i <= 3 && j >= 1 && j <= 3;
      p[inside ? (i - 1) * 3 + (j - 1) : 9] += x[i] * y[j];
    }
  }
  return p;
}

std::vector<double> Diagonal() {  // both records of a pair jitter alike
  std::vector<double> p(257, 0.0);
  for (int ax = 0; ax < 4; ++ax) {
    for (int ay = 0; ay < 4; ++ay) p[((ax * 4 + ay) * 4 + ax) * 4 + ay] = 1.0 / 16.0;
  }
  return p;
}

std::vector<Alternative> Alternatives(const JitterExperiment& level) {
  auto tangent_only = [](JitterExperiment& e) {
    for (Record& r : e.records) r.bitangent = glm::vec4(0.0f);
  };
  auto amplitude = [](JitterExperiment& e) { e.params.jitter_scale *= 1.1f; };
  auto drop = [](int field) {
    return [field](JitterExperiment& e) {
      for (Record& r : e.records) r.path[field] = field == 2 ? shared::kRecordHasVertex : 0u;
    };
  };
  // The level change of a pass that keeps the level before the jitter: none.
  auto keep_level = [level](std::vector<KeyResult> keys) {
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const Record& r = level.records[i];
      const float d = shared::PathLength(r.position.w, glm::vec3(r.position), glm::vec3(r.previous));
      keys[i].level =
          shared::LevelOfDetail(level.params.footprint_scale, d, level.params.level_min, level.params.level_max);
    }
    return keys;
  };
  const std::vector<double> uniform = ScaledOffsetBins(1.0), wide = ScaledOffsetBins(1.1);
  const std::vector<double> unit = KernelAxis(1.0), single = {0.0, 0.0, 1.0, 0.0, 0.0};
  return {
      {"tangent only", JitterTest::kSquare, tangent_only, nullptr, Square(uniform, AtBinEight())},
      {"amplitude +10%", JitterTest::kSquare, amplitude, nullptr, Square(wide, wide)},
      {"pixel dropped", JitterTest::kPixelPairs, drop(0), nullptr, Diagonal()},
      {"sample dropped", JitterTest::kSamplePairs, drop(1), nullptr, Diagonal()},
      {"bounce dropped", JitterTest::kBouncePairs, drop(2), nullptr, Diagonal()},
      {"amplitude +10%", JitterTest::kKernel, amplitude, nullptr, Kernel(KernelAxis(1.1), KernelAxis(1.1))},
      {"tangent only", JitterTest::kKernel, tangent_only, nullptr, Kernel(unit, single)},
      {"level kept (D5)", JitterTest::kLevelChange, nullptr, keep_level, {0.0, 1.0, 0.0, 0.0}},
  };
}

TEST(JitterStatistics, RejectsEachAlternativeWithItsPowerShown) {
  const JitterExperiment level = MakeJitterExperiment(JitterTest::kLevelChange, kSeed, 0, kSamples);
  for (const Alternative& alternative : Alternatives(level)) {
    JitterExperiment e = MakeJitterExperiment(alternative.test, kSeed, 0, kSamples);
    if (alternative.plant) alternative.plant(e);
    KeyPassFunction pass = CoreKeyPass;
    if (alternative.alter) {
      pass = [&](std::span<const Record> r, const KeyParams& p) { return alternative.alter(CoreKeyPass(r, p)); };
    }
    const JitterVerdict v = RunJitterTest(pass, e);
    const Power power = PowerAgainst(e.probabilities, alternative.probabilities, double(v.samples), kAlpha);
    std::printf("%-13s %-16s %s; noncentrality %.0f, type II error %.2g\n", ToString(alternative.test),
                alternative.name, v.chi_square.ToString().c_str(), power.noncentrality, 1.0 - power.power);
    EXPECT_LT(v.chi_square.p_value, kAlpha) << ToString(alternative.test) << ", " << alternative.name;
    EXPECT_GT(power.power, kMinPower) << ToString(alternative.test) << ", " << alternative.name;
  }
}

// A jitter 4% short on its negative side moves the mean offset by 0.01 of the amplitude: the z-scores' sum has
// noncentrality (0.01 / sd)^2 with sd = sqrt(1/3 / N).
TEST(JitterStatistics, TheMeanRejectsAJitterShortOnOneSide) {
  const JitterExperiment e = MakeJitterExperiment(JitterTest::kMean, kSeed, 0, kMeanSamples);
  const KeyPassFunction short_side = [](std::span<const Record> r, const KeyParams& p) {
    std::vector<KeyResult> keys = CoreKeyPass(r, p);
    for (KeyResult& k : keys) {
      const double a = (int(k.words.cell_x) + 0.5) / 64.0;
      if (a < 0.0) k.words.cell_x = std::uint32_t(int(std::floor(64.0 * 0.96 * a)));
    }
    return keys;
  };
  const JitterVerdict v = RunJitterTest(short_side, e);
  const double noncentrality = std::pow(0.01 / std::sqrt(1.0 / 3.0 / kMeanSamples), 2.0);
  const boost::math::chi_squared null(2);
  const double critical = boost::math::quantile(boost::math::complement(null, kAlpha));
  const double power =
      boost::math::cdf(boost::math::complement(boost::math::non_central_chi_squared(2, noncentrality), critical));
  std::printf("mean, 4%% short on one side: %s; noncentrality %.0f, type II error %.2g\n",
              v.chi_square.ToString().c_str(), noncentrality, 1.0 - power);
  EXPECT_LT(v.chi_square.p_value, kAlpha);
  EXPECT_GT(power, kMinPower);
}

// The offset x' - x against the normal, for records with random frames, positions up to 1e7 and amplitudes
// from 2^-20 to 2^20 (every random number from the counter RNG). Each step of the jitter rounds once: a T and
// b B (u each), their sum (u), the amplitude's product (u) and x + offset (u |x'|), plus a flushed denormal
// (2^-126) per step; and the frame itself is only as orthogonal as |T.n| and |B.n|. Bound per record:
// A (|a| |T.n| + |b| |B.n|) + sum_i |n_i| (3.01 u A (|a T_i| + |b B_i|) + u |x'_i| + 4 * 2^-126).
TEST(JitterStatistics, TheOffsetStaysInTheTangentPlaneToItsRoundingBound) {
  auto random = [](std::uint32_t i, std::uint32_t dimension) {
    return shared::RandomFloat(shared::RngCounter{kSeed, 0u, i, 0u, 0u}, dimension);
  };
  const double u = std::ldexp(1.0, -24), tiny = std::ldexp(1.0, -126);
  std::uint64_t d4_outside = 0;
  constexpr std::uint32_t kRecords = 100000;
  double worst = 0.0;  // the largest deviation as a share of its bound
  for (std::uint32_t i = 0; i < kRecords; ++i) {
    const glm::vec3 normal = glm::normalize(glm::vec3(random(i, 0), random(i, 1), random(i, 2)) * 2.0f - 1.0f);
    VertexSample v;
    v.normal = normal;
    const float scale = std::pow(10.0f, 7.0f * random(i, 6));
    v.position = (glm::vec3(random(i, 3), random(i, 4), random(i, 5)) * 2.0f - 1.0f) * scale;
    const Record r = MakeVertexRecord(v);
    const glm::vec3 x(r.position), n(r.normal), t(r.tangent), b(r.bitangent);
    const float amplitude = std::ldexp(1.0f, int(40.0f * random(i, 7)) - 20);
    const float u1 = random(i, 8), u2 = random(i, 9), ea = 2.0f * u1 - 1.0f, eb = 2.0f * u2 - 1.0f;
    const glm::vec3 jittered = shared::JitterInTangentPlane(x, t, b, amplitude, u1, u2);
    const double tn = std::abs(glm::dot(glm::dvec3(t), glm::dvec3(n)));
    const double bn = std::abs(glm::dot(glm::dvec3(b), glm::dvec3(n)));
    double deviation = 0.0, bound = double(amplitude) * (std::abs(double(ea)) * tn + std::abs(double(eb)) * bn);
    for (int c = 0; c < 3; ++c) {
      deviation += (double(jittered[c]) - double(x[c])) * double(n[c]);
      const double products = std::abs(double(ea * t[c])) + std::abs(double(eb * b[c]));
      const double rounding = 3.01 * u * amplitude * products + u * std::abs(double(jittered[c])) + 4.0 * tiny;
      bound += std::abs(double(n[c])) * rounding;
    }
    ASSERT_LE(std::abs(deviation), bound)
        << "record " << i << ": normal " << normal.x << " " << normal.y << " " << normal.z;
    worst = std::max(worst, std::abs(deviation) / bound);
    // D4: a random direction d projected as d - |n| d (componentwise) instead of d - n (n.d).
    const glm::vec3 d = ea * t + eb * b + (2.0f * random(i, 10) - 1.0f) * n;
    const glm::vec3 d4 = x + amplitude * (d - glm::abs(n) * d);
    double d4_deviation = 0.0;
    for (int c = 0; c < 3; ++c) d4_deviation += (double(d4[c]) - double(x[c])) * double(n[c]);
    d4_outside += std::abs(d4_deviation) > bound;
  }
  std::printf("largest deviation %.3g of its bound; D4's projection outside the bound for %llu of %u records\n", worst,
              (unsigned long long)d4_outside, kRecords);
  EXPECT_GT(d4_outside, kRecords / 2);
}

}  // namespace
}  // namespace hpsf::testing
