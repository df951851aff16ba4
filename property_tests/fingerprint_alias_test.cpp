// Fingerprint failures: how often two different keys share a slot because their b-bit fingerprints are equal
// within a probe window, against the rate predicted from the window occupancy (verifier/theory/alias_theory). For
// b = 8, 10, 12, 16, 20 crowded tables (2^16 slots, 90% of them offered distinct keys, probe limit 16) are filled
// one key at a time; given the table each key meets, its chance of an alias is exact, and their sum is the
// prediction. H0: the aliases counted have that expectation. The count is a sum of independent-given-the-past
// trials with these chances; a binomial with the same mean has at least its variance, so the Clopper-Pearson
// interval of the measured rate (Boost.Math) is conservative. Sidak over the 4 widths, family at 0.001.
// Alternatives it must reject, shown below with the same statistic and keys: fingerprints that keep the low
// bits of the index hash (the bits that chose the slot, so keys crowding a window share them) and fingerprints
// two bits short of their width (four times the aliases), both at every width. kResolution states the power.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include <boost/math/distributions/binomial.hpp>
#include <gtest/gtest.h>

#include "core/key_batch.h"
#include "emulated/emulated_filter.h"
#include "property_tests/grid_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "verifier/theory/alias_theory.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kSlots = 1u << 16;
constexpr std::uint32_t kProbeLimit = 16;
constexpr double kLoad = 0.9;
constexpr int kTables = 20;
constexpr std::uint32_t kBits[] = {8, 10, 12, 16};
// The power stated per width: the interval's upper end is below this multiple of the prediction (measured:
// 1.02, 1.02, 1.12, 1.83), so a fingerprint that aliases more often than that is rejected.
constexpr double kResolution[] = {1.1, 1.15, 1.3, 2.5};
const double kAlpha = 1.0 - std::pow(1.0 - 0.001, 1.0 / std::size(kBits));  // Sidak, per width

// The fingerprint a variant would store, from the key path's result at `bits`.
using FingerprintFunction = std::function<std::uint32_t(const KeyResult& key, std::uint32_t bits)>;
std::uint32_t TheFingerprint(const KeyResult& key, std::uint32_t) { return key.fingerprint; }
std::uint32_t LowBitsOfTheIndexHash(const KeyResult& key, std::uint32_t bits) {
  const std::uint32_t low = shared::IndexHash(key.words, 0u) & ((1u << bits) - 1u);
  return low == 0u ? 1u : low;
}
std::uint32_t TwoBitsShort(const KeyResult& key, std::uint32_t) { return std::max(key.fingerprint >> 2, 1u); }

std::vector<KeyResult> TableKeys(int table, std::uint32_t bits) {
  const std::uint32_t keys = std::uint32_t(kLoad * kSlots);
  const RecordBatch batch = GridBatch(table, keys);
  FilterConfig config = GridConfig(kSlots, kProbeLimit);
  config.fingerprint_bits = bits;
  return ComputeKeys(batch.records, MakeKeyParams(config, 1.0f, keys));
}

AliasTally TallyTables(std::uint32_t bits, const FingerprintFunction& fingerprint) {
  AliasTally total;
  for (int table = 0; table < kTables; ++table) {
    std::vector<KeyResult> keys = TableKeys(table, bits);
    for (KeyResult& k : keys) k.fingerprint = fingerprint(k, bits);
    const AliasTally t = InsertAndCountAliases(keys, kSlots, kProbeLimit, bits);
    total.keys += t.keys;
    total.aliased += t.aliased;
    total.failed += t.failed;
    total.predicted += t.predicted;
    total.variance += t.variance;
    total.compared += t.compared;
  }
  return total;
}

struct Interval {
  double low = 0.0, high = 1.0;
  bool Holds(double rate) const { return low <= rate && rate <= high; }
};

Interval ClopperPearson(const AliasTally& t, double alpha) {
  using boost::math::binomial_distribution;
  return {binomial_distribution<>::find_lower_bound_on_p(double(t.keys), double(t.aliased), alpha / 2),
          binomial_distribution<>::find_upper_bound_on_p(double(t.keys), double(t.aliased), alpha / 2)};
}

TEST(FingerprintAliases, TheRateAtEveryWidthIsTheOnePredictedFromTheWindows) {
  double aliased = 0.0, predicted = 0.0, compared_per_key = 0.0;
  for (std::size_t b = 0; b < std::size(kBits); ++b) {
    const AliasTally t = TallyTables(kBits[b], TheFingerprint);
    const Interval interval = ClopperPearson(t, kAlpha);
    std::printf(
        "%2u bits: %llu of %llu keys aliased (rate %.4g, interval [%.4g, %.4g]), predicted %.4g, "
        "%.3f tags compared per key, %llu probe failures\n",
        kBits[b], (unsigned long long)t.aliased, (unsigned long long)t.keys, t.Rate(), interval.low, interval.high,
        t.PredictedRate(), t.compared / double(t.keys), (unsigned long long)t.failed);
    EXPECT_TRUE(interval.Holds(t.PredictedRate()))
        << kBits[b] << " bits: rate " << t.Rate() << ", predicted " << t.PredictedRate();
    EXPECT_LT(interval.high, kResolution[b] * t.PredictedRate()) << kBits[b] << " bits: too little power";
    aliased += double(t.aliased);
    predicted += t.predicted;
    compared_per_key = t.compared / double(t.keys);
  }
  // The 32-bit rate is far too small to count; extrapolated from the widths measured: the observed share of
  // the predicted aliases, times the chance at 32 bits of the tags a key compares at the widest width.
  const double observed_over_predicted = aliased / predicted;
  std::printf("32 bits, extrapolated: %.3g aliases per key (observed / predicted over all widths %.4f)\n",
              observed_over_predicted * compared_per_key * std::ldexp(1.0, -32), observed_over_predicted);
}

TEST(FingerprintAliases, RejectsFingerprintsFromTheIndexBitsAndFingerprintsTwoBitsShort) {
  for (const FingerprintFunction& alternative :
       {FingerprintFunction(LowBitsOfTheIndexHash), FingerprintFunction(TwoBitsShort)}) {
    for (const std::uint32_t bits : kBits) {
      const AliasTally t = TallyTables(bits, alternative);
      EXPECT_FALSE(ClopperPearson(t, kAlpha).Holds(t.PredictedRate()))
          << bits << " bits: rate " << t.Rate() << ", predicted " << t.PredictedRate();
    }
  }
}

// The backends store the key path's fingerprints, so their aliases follow the same law; they insert in their
// own order, so a backend's count is held to the prediction within a bound a correct run never leaves
// (six standard deviations): it catches a backend that aliases where the sequential table would not.
TEST(FingerprintAliases, BackendsAliasAsOftenAsPredicted) {
  const std::uint32_t bits = 8;
  const std::uint32_t count = std::uint32_t(kLoad * kSlots);
  const RecordBatch batch = GridBatch(0, count);
  FilterConfig config = GridConfig(kSlots, kProbeLimit);
  config.fingerprint_bits = bits;
  const AliasTally theory = InsertAndCountAliases(TableKeys(0, bits), kSlots, kProbeLimit, bits);
  const double bound = 6.0 * std::sqrt(theory.variance);
  // Every record is its own key: a slot's records beyond the first are aliases.
  auto aliases = [](const HashedRun& run) {
    std::uint64_t n = 0;
    for (const std::uint32_t c : run.table.counts) n += c > 1 ? c - 1 : 0;
    return double(n);
  };
  for (const simt::Mode mode : {simt::Mode::kFaithful, simt::Mode::kFast}) {
    EmulatorOptions options;
    options.mode = mode;
    const double n = aliases(EmulatedFilter(batch, config, options));
    EXPECT_NEAR(n, theory.predicted, bound) << "emulated, " << (mode == simt::Mode::kFast ? "fast" : "faithful");
  }
  for (const StagingPolicy staging : kStagingPolicies) {
    EXPECT_NEAR(aliases(TestFilter(staging).Run(batch, config)), theory.predicted, bound) << "vulkan";
  }
  std::printf("8 bits, one table: %.0f predicted, %llu in the sequential table, bound +-%.0f\n", theory.predicted,
              (unsigned long long)theory.aliased, bound);
}

}  // namespace
}  // namespace hpsf::testing
