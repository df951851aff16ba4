// Collisions: the index hash against linear probing's theory (verifier/theory/probe_theory). For each load a in
// {0.1, 0.25, 0.5, 0.7, 0.8, 0.9, 0.95}, 20 tables are filled with distinct keys and two statistics measured per
// table: the mean probes of a successful search, and the share of its windows of 4 and of 16 slots that are full
// (the probability that a new key exceeds a probe limit of that size). H0: their expectations are the exact
// values for uniform hashing. A two-sided t-test on the 20 table figures (Student's t from Boost.Math, 19
// degrees of freedom), Sidak-corrected so that each family (7 loads x 3 statistics) holds at 0.001. The keys are
// generated (translated grids of cells, 2^16 slots per table) and real: the distinct keys of the Cornell box at
// 1080p, one sample per pixel, in the order the pixels first meet them, 20 consecutive runs of them per load in
// tables of 2^14 slots. Fixed keys: the verdict never changes between runs.
// Alternatives it must reject, shown below with the same statistic: an index hash that clusters (the sum of
// the cell coordinates) and one that drops words (the x coordinate alone), both rejected at every load from 0.5
// (in tables of 2^13 slots); kResolution below states the power against any other shift of the mean.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <boost/math/distributions/students_t.hpp>
#include <gtest/gtest.h>

#include "core/footprint.h"
#include "core/key_batch.h"
#include "emulated/emulated_filter.h"
#include "property_tests/grid_batch.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "verifier/theory/probe_theory.h"
#include "verifier/theory/table_statistics.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kSlots = 1u << 16;
constexpr std::uint32_t kSmallSlots = 1u << 13;  // enough for the alternatives, whose clusters make them slow
constexpr int kTables = 20;
constexpr double kLoads[] = {0.1, 0.25, 0.5, 0.7, 0.8, 0.9, 0.95};
// The power stated per load: the interval's half width is below this share of the theory (measured: 0.38%,
// 0.26%, 0.82%, 1.1%, 1.5%, 3.2%, 8.1%); a hash that shifts the mean probes by more is rejected.
constexpr double kResolution[] = {0.01, 0.01, 0.01, 0.015, 0.02, 0.04, 0.09};
// A figure is tested only where the 20 tables expect at least this many full windows in all: below it (windows
// of 16 at loads 0.1 and 0.25) nearly every table measures 0 and the t-test has nothing to judge.
constexpr double kFewestExpectedEvents = 10.0;
constexpr std::uint32_t kWindows[] = {4, 16};  // probe limits whose overflow probability is tested
// Sidak, per test of a family of 7 loads x (probes + 2 windows).
const double kAlpha = 1.0 - std::pow(1.0 - 0.001, 1.0 / (std::size(kLoads) * (1 + std::size(kWindows))));

using IndexFunction = std::uint32_t (*)(const KeyResult& key);
std::uint32_t TheIndexHash(const KeyResult& key) { return key.slot0; }
std::uint32_t SumOfCoordinates(const KeyResult& key) { return key.words.cell_x + key.words.cell_y + key.words.cell_z; }
std::uint32_t XAlone(const KeyResult& key) { return key.words.cell_x; }

struct LoadVerdict {
  double theory = 0.0, mean = 0.0, half_width = 0.0, p_value = 1.0;
  bool tested = true;
};

// A two-sided t-test of H0: E[figure] = theory, from one figure per table.
LoadVerdict TTest(const std::vector<double>& figures, double theory) {
  LoadVerdict v;
  v.theory = theory;
  const double n = double(figures.size());
  double sum = 0.0, squares = 0.0;
  for (double m : figures) sum += m;
  v.mean = sum / n;
  for (double m : figures) squares += (m - v.mean) * (m - v.mean);
  const double standard_error = std::sqrt(squares / (n - 1) / n);
  const boost::math::students_t t(n - 1);
  v.half_width = boost::math::quantile(boost::math::complement(t, kAlpha / 2)) * standard_error;
  v.p_value = standard_error > 0.0
                  ? 2.0 * boost::math::cdf(boost::math::complement(t, std::abs(v.mean - v.theory) / standard_error))
                  : (v.mean == v.theory ? 1.0 : 0.0);
  return v;
}

// A table's figure from its keys' first slots, and the theory for uniform hashing; window 0 is the mean probes.
struct Statistic {
  std::uint32_t window = 0;
  double Measure(const std::vector<std::uint32_t>& slot0s, std::uint32_t slots) const {
    return window == 0 ? MeasuredProbesOnHit(slot0s, slots) : MeasuredWindowFullShare(slot0s, slots, window);
  }
  double Theory(std::uint32_t slots, std::uint32_t keys) const {
    return window == 0 ? ExpectedProbesOnHit(slots, keys) : ProbabilityWindowFull(slots, keys, window);
  }
  std::string Name() const { return window == 0 ? "mean probes" : "full windows of " + std::to_string(window); }
};
const Statistic kStatistics[] = {{0}, {kWindows[0]}, {kWindows[1]}};

// Table t's keys at load `load`: their first slots (unmasked).
using TableKeys = std::function<std::vector<std::uint32_t>(int table, std::uint32_t keys)>;

std::vector<LoadVerdict> TestLoad(double load, const TableKeys& table_keys, std::uint32_t slots) {
  const std::uint32_t keys = std::uint32_t(load * slots);
  std::vector<std::vector<double>> figures(std::size(kStatistics));
  for (int table = 0; table < kTables; ++table) {
    const std::vector<std::uint32_t> slot0s = table_keys(table, keys);
    for (std::size_t s = 0; s < std::size(kStatistics); ++s)
      figures[s].push_back(kStatistics[s].Measure(slot0s, slots));
  }
  std::vector<LoadVerdict> verdicts;
  for (std::size_t s = 0; s < std::size(kStatistics); ++s) {
    verdicts.push_back(TTest(figures[s], kStatistics[s].Theory(slots, keys)));
    if (kStatistics[s].window != 0)
      verdicts.back().tested = verdicts.back().theory * slots * kTables >= kFewestExpectedEvents;
  }
  return verdicts;
}

TableKeys GridKeys(IndexFunction index, std::uint32_t slots) {
  return [index, slots](int table, std::uint32_t keys) {
    const RecordBatch batch = GridBatch(table, keys);
    const std::vector<KeyResult> results = ComputeKeys(batch.records, MakeKeyParams(GridConfig(slots), 1.0f, keys));
    std::vector<std::uint32_t> slot0s;
    for (const KeyResult& k : results) slot0s.push_back(index(k));
    return slot0s;
  };
}

// The distinct keys of the Cornell box at 1080p (default filter), in the order the pixels first meet them.
const std::vector<std::uint32_t>& CornellSlot0s() {
  static const std::vector<std::uint32_t> slot0s = [] {
    TraceOptions trace;
    trace.width = 1920;
    trace.height = 1080;
    trace.samples_per_pixel = 1;
    const RecordBatch batch = TraceRecords(LoadScene("cornell"), trace).batch;
    const FilterConfig config;
    const float footprint = FootprintScale(config.filter_width_px, batch.fov_y_radians, batch.height);
    const std::vector<KeyResult> keys =
        ComputeKeys(batch.records, MakeKeyParams(config, footprint, std::uint32_t(batch.records.size())));
    std::vector<std::uint32_t> distinct;
    for (const KeyResult& k : DistinctKeys(keys)) distinct.push_back(k.slot0);
    return distinct;
  }();
  return slot0s;
}

void Report(const char* keys, double load, const Statistic& statistic, const LoadVerdict& v) {
  std::printf("%s keys, load %.2f, %s: measured %.6g, theory %.6g, p %.3g, interval +-%.3g%s\n", keys, load,
              statistic.Name().c_str(), v.mean, v.theory, v.p_value, v.half_width,
              v.tested ? "" : " (too rare to test)");
}

// The theory itself, against every hash sequence of small tables enumerated: the exact mean over all M^N
// equally likely sequences of slot0s.
TEST(CollisionStatistics, KnuthsExpectationEqualsEnumerationOfSmallTables) {
  for (std::uint32_t slots : {2u, 4u, 8u}) {
    for (std::uint32_t keys = 1; keys < slots && keys <= 5; ++keys) {
      std::uint64_t sequences = 1;
      for (std::uint32_t k = 0; k < keys; ++k) sequences *= slots;
      double hits = 0.0, misses = 0.0;
      std::vector<double> full_windows(slots, 0.0);  // [w]: windows of w slots found full
      std::vector<std::uint32_t> slot0s(keys);
      for (std::uint64_t code = 0; code < sequences; ++code) {
        std::uint64_t rest = code;
        std::vector<bool> taken(slots, false);
        for (std::uint32_t& s : slot0s) {
          s = std::uint32_t(rest % slots);
          rest /= slots;
          std::uint32_t slot = s;
          while (taken[slot]) slot = (slot + 1) % slots;
          taken[slot] = true;
        }
        hits += MeasuredProbesOnHit(slot0s, slots);
        for (std::uint32_t w = 1; w < slots; ++w) full_windows[w] += MeasuredWindowFullShare(slot0s, slots, w);
        for (std::uint32_t s = 0; s < slots; ++s) {  // a search for a key not in the table, from every slot
          for (std::uint32_t slot = s;; slot = (slot + 1) % slots) {
            misses += 1.0 / slots;
            if (!taken[slot]) break;
          }
        }
      }
      EXPECT_NEAR(hits / double(sequences), ExpectedProbesOnHit(slots, keys), 1e-12)
          << keys << " keys in " << slots << " slots";
      EXPECT_NEAR(misses / double(sequences), ExpectedProbesOnMiss(slots, keys), 1e-12)
          << keys << " keys in " << slots << " slots";
      for (std::uint32_t w = 1; w < slots; ++w) {
        EXPECT_NEAR(full_windows[w] / double(sequences), ProbabilityWindowFull(slots, keys, w), 1e-12)
            << "window " << w << ", " << keys << " keys in " << slots << " slots";
      }
    }
  }
}

TEST(CollisionStatistics, TheIndexHashProbesAsUniformHashingDoesAtEveryLoad) {
  for (std::size_t l = 0; l < std::size(kLoads); ++l) {
    const double load = kLoads[l];
    const std::vector<LoadVerdict> verdicts = TestLoad(load, GridKeys(TheIndexHash, kSlots), kSlots);
    for (std::size_t s = 0; s < verdicts.size(); ++s) {
      const LoadVerdict& v = verdicts[s];
      Report("generated", load, kStatistics[s], v);
      if (!v.tested) continue;
      EXPECT_GT(v.p_value, kAlpha) << "load " << load << ", " << kStatistics[s].Name() << ": " << v.mean << ", theory "
                                   << v.theory;
    }
    EXPECT_LT(verdicts[0].half_width, kResolution[l] * verdicts[0].theory) << "load " << load << ": too little power";
  }
}

TEST(CollisionStatistics, TheCornellBoxAt1080pProbesAsUniformHashingDoes) {
  constexpr std::uint32_t kCornellSlots = 1u << 14;
  const std::vector<std::uint32_t>& distinct = CornellSlot0s();
  ASSERT_GE(distinct.size(), std::size_t(kTables * 0.95 * kCornellSlots)) << "too few distinct keys for the loads";
  const TableKeys cornell = [&](int table, std::uint32_t keys) {
    const auto first = distinct.begin() + std::ptrdiff_t(table) * keys;
    return std::vector<std::uint32_t>(first, first + keys);
  };
  for (const double load : kLoads) {
    const std::vector<LoadVerdict> verdicts = TestLoad(load, cornell, kCornellSlots);
    for (std::size_t s = 0; s < verdicts.size(); ++s) {
      Report("Cornell 1080p", load, kStatistics[s], verdicts[s]);
      if (!verdicts[s].tested) continue;
      EXPECT_GT(verdicts[s].p_value, kAlpha) << "load " << load << ", " << kStatistics[s].Name() << ": "
                                             << verdicts[s].mean << ", theory " << verdicts[s].theory;
    }
  }
}

TEST(CollisionStatistics, RejectsAClusteringHashAndOneThatDropsWords) {
  for (const IndexFunction alternative : {SumOfCoordinates, XAlone}) {
    for (const double load : kLoads) {
      if (load < 0.5) continue;
      const LoadVerdict v = TestLoad(load, GridKeys(alternative, kSmallSlots), kSmallSlots)[0];
      EXPECT_LT(v.p_value, kAlpha) << "load " << load << ": mean " << v.mean << ", theory " << v.theory;
    }
  }
}

// Each backend's probe-length histogram is the table's: its mean equals linear probing's over the same slot0s
// exactly, in fast mode too, since the total displacement does not depend on the order of insertion.
TEST(CollisionStatistics, BackendProbeHistogramsAreTheTablesMean) {
  for (const double load : {0.5, 0.9}) {
    const std::uint32_t keys = std::uint32_t(load * kSlots);
    const RecordBatch batch = GridBatch(0, keys);
    const FilterConfig config = GridConfig(kSlots);
    const std::vector<KeyResult> results = ComputeKeys(batch.records, MakeKeyParams(config, 1.0f, keys));
    std::vector<std::uint32_t> slot0s;
    for (const KeyResult& k : results) slot0s.push_back(k.slot0);
    const double expected = MeasuredProbesOnHit(slot0s, kSlots);
    auto mean = [](const HashedRun& run) {
      double probes = 0.0, placed = 0.0;
      for (std::size_t k = 0; k < run.probe_lengths.size(); ++k) {
        probes += double(k + 1) * double(run.probe_lengths[k]);
        placed += double(run.probe_lengths[k]);
      }
      return probes / placed;
    };
    EXPECT_DOUBLE_EQ(mean(EmulatedFilter(batch, config, EmulatorOptions{})), expected) << "emulated, load " << load;
    EXPECT_DOUBLE_EQ(mean(TestFilter(StagingPolicy::kAuto).Run(batch, config)), expected) << "vulkan, load " << load;
  }
}

}  // namespace
}  // namespace hpsf::testing
