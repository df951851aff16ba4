#include "verifier/theory/table_statistics.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>

#include <boost/math/distributions/binomial.hpp>

#include "core/shared/levels.h"
#include "verifier/theory/alias_theory.h"
#include "verifier/theory/probe_theory.h"

namespace hpsf {
namespace {

constexpr double kLevel = 0.001;
constexpr std::uint32_t kProbeLimits[] = {1, 2, 4, 8, 16, 32, 64};
constexpr std::uint32_t kFingerprintBits[] = {8, 10, 12, 16, 24, 32};
constexpr std::uint32_t kHistogramProbes = 16;  // the histogram's last bucket holds every longer search
constexpr int kFills = 16;                      // a rate over the fill is the mean at this many loads
constexpr std::uint32_t kJitterSamples = 1u << 16, kJitterMeanSamples = 1u << 18;

RateFigure Rate(std::uint64_t events, std::uint64_t trials, double theory, double alpha) {
  RateFigure f{events, trials, theory, 0.0, 1.0};
  if (trials == 0) return f;
  using boost::math::binomial_distribution;
  f.low = binomial_distribution<>::find_lower_bound_on_p(double(trials), double(events), alpha / 2);
  f.high = binomial_distribution<>::find_upper_bound_on_p(double(trials), double(events), alpha / 2);
  return f;
}

// A key inserted while the table fills from 0 to `keys` meets, on average over the fill, a full window of
// `window` slots with this probability (the mean at kFills evenly spaced loads). Once the keys fill every slot, every
// window is full; before, a window of the whole table still holds an empty slot. Memoized by window: the histogram
// and the probe limits ask for the same ones.
class WindowFullOverTheFill {
 public:
  WindowFullOverTheFill(std::uint64_t slots, std::uint64_t keys) : slots_(slots), keys_(keys) {}
  double operator()(std::uint64_t window) {
    if (window == 0) return 1.0;
    const auto [it, added] = known_.emplace(window, 0.0);
    if (!added) return it->second;
    for (int fill = 0; fill < kFills; ++fill) {
      const auto keys = std::uint64_t((fill + 0.5) / kFills * double(keys_));
      it->second += keys >= slots_ ? 1.0 : window >= slots_ ? 0.0 : ProbabilityWindowFull(slots_, keys, window);
    }
    return it->second /= kFills;
  }

 private:
  std::uint64_t slots_, keys_;
  std::map<std::uint64_t, double> known_;
};

std::vector<std::uint32_t> SortedWith(std::span<const std::uint32_t> values, std::uint32_t extra) {
  std::vector<std::uint32_t> all(values.begin(), values.end());
  all.push_back(extra);
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

nlohmann::json RateJson(const RateFigure& f) {
  return {{"events", f.events},
          {"trials", f.trials},
          {"rate", f.Rate()},
          {"theory", f.judged ? nlohmann::json(f.theory) : nlohmann::json(nullptr)},
          {"interval", {f.low, f.high}},
          {"exceeds_theory", f.ExceedsTheory()}};
}

}  // namespace

bool TableStatistics::ExceedsTheory() const {
  for (const ProbeLimitFigure& f : probe_limits) {
    if (f.failures.ExceedsTheory()) return true;
  }
  for (const AliasFigure& f : fingerprints) {
    if (f.aliases.ExceedsTheory()) return true;
  }
  for (const JitterVerdict& v : jitter) {
    if (v.chi_square.p_value <= jitter_alpha) return true;
  }
  return false;
}

std::vector<KeyResult> DistinctKeys(std::span<const KeyResult> keys, std::vector<std::uint64_t>* results_per_key) {
  std::map<std::array<std::uint32_t, 6>, std::size_t> index;
  std::vector<KeyResult> distinct;
  std::vector<std::uint64_t> per_key;
  for (const KeyResult& k : keys) {
    if (k.status != shared::kKeyed) continue;
    const std::array<std::uint32_t, 6> words = {k.words.cell_x, k.words.cell_y, k.words.cell_z,
                                                k.words.level,  k.words.normal, k.words.extra};
    const auto [it, added] = index.emplace(words, distinct.size());
    if (added) {
      distinct.push_back(k);
      per_key.push_back(0);
    }
    ++per_key[it->second];
  }
  if (results_per_key != nullptr) *results_per_key = std::move(per_key);
  return distinct;
}

namespace {

// [b]: keys with 2^b .. 2^(b+1) - 1 results.
std::vector<std::uint64_t> Log2Histogram(const std::vector<std::uint64_t>& per_key) {
  std::vector<std::uint64_t> histogram;
  for (const std::uint64_t n : per_key) {
    const std::size_t bucket = std::size_t(std::bit_width(n) - 1);
    if (histogram.size() <= bucket) histogram.resize(bucket + 1, 0);
    ++histogram[bucket];
  }
  return histogram;
}

}  // namespace

std::vector<std::vector<std::uint64_t>> RecordsPerCoarserCell(std::span<const KeyResult> keys, const KeyParams& params,
                                                              std::uint32_t levels) {
  std::vector<std::vector<std::uint64_t>> by_level;
  std::vector<KeyResult> coarser(keys.size());
  for (std::uint32_t k = 1; k < levels; ++k) {
    for (std::size_t i = 0; i < keys.size(); ++i) coarser[i] = shared::KeyAtLevel(params, keys[i], k);
    std::vector<std::uint64_t> per_key;
    DistinctKeys(coarser, &per_key);
    by_level.push_back(Log2Histogram(per_key));
  }
  return by_level;
}

namespace {

// hpsf_keys: the keys are hpsf's, whose fingerprint at any width is recomputed from the key words, and whose jitter
// is tested; else the identities are taken as given, at the declared width only.
TableStatistics MeasureStatistics(std::uint64_t records, std::span<const KeyResult> keys, const FilterConfig& config,
                                  bool hpsf_keys) {
  TableStatistics s;
  s.records = records;
  s.capacity = config.capacity;
  s.probe_limit = config.probe_limit;
  s.probing = config.probing;
  s.fingerprint_bits = config.fingerprint_bits;
  s.key_identity = config.key_identity;

  std::vector<std::uint64_t> per_key;
  const std::vector<KeyResult> distinct = DistinctKeys(keys, &per_key);
  for (const std::uint64_t n : per_key) s.keyed_records += n;
  s.distinct_keys = distinct.size();
  s.load = double(s.distinct_keys) / double(s.capacity);
  s.records_per_cell = Log2Histogram(per_key);
  for (const std::uint64_t n : per_key) s.max_records_per_cell = std::max(s.max_records_per_cell, n);
  if (distinct.empty()) return s;

  WindowFullOverTheFill window_full(s.capacity, s.distinct_keys);
  std::vector<std::uint32_t> limits = SortedWith(kProbeLimits, config.probe_limit);
  std::erase_if(limits, [&](std::uint32_t limit) { return limit > s.capacity; });
  const std::vector<std::uint32_t> widths = hpsf_keys ? SortedWith(kFingerprintBits, config.fingerprint_bits)
                                                      : std::vector<std::uint32_t>{config.fingerprint_bits};
  const double alpha = SidakLevel(kLevel, int(limits.size() + widths.size()));

  if (s.distinct_keys < s.capacity) {
    std::vector<std::uint32_t> slot0s;
    for (const KeyResult& k : distinct) slot0s.push_back(k.slot0);
    s.probe_histogram.assign(kHistogramProbes, 0.0);
    for (const std::uint32_t probes : ProbesOnHit(slot0s, s.capacity)) {
      s.probe_histogram[std::min(probes, kHistogramProbes) - 1] += 1.0 / double(s.distinct_keys);
      s.mean_probes += double(probes) / double(s.distinct_keys);
    }
    // A key found after k probes was inserted when a window of k - 1 slots from its slot0 was full and one of k
    // was not.
    for (std::uint32_t k = 1; k <= kHistogramProbes; ++k) {
      s.probe_histogram_theory.push_back(k == kHistogramProbes ? window_full(k - 1)
                                                               : window_full(k - 1) - window_full(k));
    }
    s.mean_probes_theory = ExpectedProbesOnHit(s.capacity, s.distinct_keys);
  }

  // Failures under the table's own scheme. Linear probing and aligned buckets have exact theories (upper bounds,
  // since an aliasing key takes no slot); bucket-window's windows pile up against the table's end, which no closed
  // form here follows, so its rates are reported and not judged.
  // A table of full keys stores each key whole, so no two keys alias: each is inserted with a tag of its own.
  std::vector<KeyResult> whole = distinct;
  if (config.key_identity == KeyIdentity::kFull) {
    for (std::size_t i = 0; i < whole.size(); ++i) whole[i].fingerprint = std::uint32_t(i + 1);
  }
  for (const std::uint32_t limit : limits) {
    const AliasTally t = InsertAndCountAliases(whole, s.capacity, limit, config.fingerprint_bits, config.probing);
    RateFigure failures = Rate(t.failed, t.keys, 0.0, alpha);
    if (config.probing == ProbeKind::kLinear) {
      failures.theory = std::min(1.0, window_full(limit));
    } else if (config.probing == ProbeKind::kBucket) {
      failures.theory = std::min(1.0, ExpectedBucketOverflowShare(s.capacity, s.distinct_keys, limit));
    } else {
      failures.judged = false;
    }
    s.probe_limits.push_back({limit, failures});
  }

  double observed = 0.0, predicted = 0.0, compared_per_key = 0.0;
  for (const std::uint32_t bits : widths) {
    std::vector<KeyResult> at_width = distinct;
    if (hpsf_keys) {
      for (KeyResult& k : at_width) k.fingerprint = shared::Fingerprint(k.words, bits);
    }
    const AliasTally t = InsertAndCountAliases(at_width, s.capacity, config.probe_limit, bits, config.probing);
    s.fingerprints.push_back({bits, Rate(t.aliased, t.keys, t.PredictedRate(), alpha)});
    observed += double(t.aliased);
    predicted += t.predicted;
    compared_per_key = t.compared / double(t.keys);
  }
  // The 32-bit rate is too small to count: the share of the predicted aliases observed over all widths, times
  // the chance at 32 bits of the tags a key compares.
  const double observed_share = predicted > 0.0 ? observed / predicted : 1.0;
  s.extrapolated_alias_rate_32 = observed_share * compared_per_key * std::ldexp(1.0, -32);

  if (!hpsf_keys) return s;
  s.jitter_alpha = SidakLevel(kLevel, int(std::size(kJitterTests)));
  for (const JitterTest test : kJitterTests) {
    const std::uint32_t samples = test == JitterTest::kMean ? kJitterMeanSamples : kJitterSamples;
    s.jitter.push_back(RunJitterTest(CoreKeyPass, MakeJitterExperiment(test, config.seed, config.frame, samples)));
  }
  return s;
}

}  // namespace

TableStatistics MeasureTableStatistics(std::span<const Record> records, std::span<const KeyResult> keys,
                                       const FilterConfig& config) {
  return MeasureStatistics(records.size(), keys, config, true);
}

TableStatistics MeasureGivenKeyStatistics(std::uint64_t records, std::span<const KeyResult> keys,
                                          const FilterConfig& config) {
  return MeasureStatistics(records, keys, config, false);
}

nlohmann::json TableStatistics::ToJson() const {
  nlohmann::json j = {{"records", records},
                      {"keyed_records", keyed_records},
                      {"distinct_keys", distinct_keys},
                      {"capacity", capacity},
                      {"probe_limit", probe_limit},
                      {"probing", ToString(probing)},
                      {"fingerprint_bits", fingerprint_bits},
                      {"load", load},
                      {"probes_on_hit",
                       {{"histogram", probe_histogram},
                        {"histogram_theory", probe_histogram_theory},
                        {"mean", mean_probes},
                        {"mean_theory", mean_probes_theory}}},
                      {"records_per_cell", {{"log2_histogram", records_per_cell}, {"max", max_records_per_cell}}},
                      {"records_per_coarser_cell", records_per_coarser_cell},
                      {"resolved_at_level", resolved_at_level},
                      {"records_searched", records_searched},
                      {"neighbours_read", neighbours_read},
                      {"extrapolated_alias_rate_32", extrapolated_alias_rate_32},
                      {"exceeds_theory", ExceedsTheory()}};
  for (const ProbeLimitFigure& f : probe_limits) {
    j["probe_failures"].push_back({{"probe_limit", f.probe_limit}, {"failures", RateJson(f.failures)}});
  }
  for (const AliasFigure& f : fingerprints) {
    j["aliases"].push_back({{"fingerprint_bits", f.fingerprint_bits}, {"aliases", RateJson(f.aliases)}});
  }
  j["jitter"] = nlohmann::json::array();  // empty for keys that are not hpsf's
  for (const JitterVerdict& v : jitter) {
    j["jitter"].push_back({{"test", ToString(v.test)},
                           {"samples", v.samples},
                           {"chi_square", v.chi_square.statistic},
                           {"dof", v.chi_square.dof},
                           {"p_value", v.chi_square.p_value},
                           {"rejected", v.chi_square.p_value <= jitter_alpha}});
  }
  return j;
}

}  // namespace hpsf
