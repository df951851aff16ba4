// Collisions: the index hash against linear probing's theory (tools/checks/probe_theory). For each load a in
// {0.1, 0.25, 0.5, 0.7, 0.8, 0.9, 0.95}, 20 tables of 2^16 slots are filled with distinct keys (translated grids
// of cells, a different translation per table) and the mean probes of a successful search of each table is
// measured. H0: their expectation is Knuth's exact value for uniform hashing. A two-sided t-test on the 20
// table means (Student's t from Boost.Math, 19 degrees of freedom), Sidak-corrected so that the family of 7
// loads holds at 0.001 (each test at 1.43e-4). Fixed keys: the verdict never changes between runs.
// Alternatives it must reject, shown below with the same statistic: an index hash that clusters (the sum of
// the cell coordinates) and one that drops words (the x coordinate alone), both rejected at every load from 0.5
// (in tables of 2^13 slots); kResolution below states the power against any other shift of the mean.
#include <cmath>
#include <vector>

#include <boost/math/distributions/students_t.hpp>
#include <gtest/gtest.h>

#include "core/key_batch.h"
#include "emulated/emulated_filter.h"
#include "property_tests/vulkan_test_devices.h"
#include "tools/checks/probe_theory.h"

namespace hpsf::testing {
namespace {

constexpr std::uint32_t kSlots = 1u << 16;
constexpr std::uint32_t kSmallSlots = 1u << 13;  // enough for the alternatives, whose clusters make them slow
constexpr int kTables = 20;
constexpr double kLoads[] = {0.1, 0.25, 0.5, 0.7, 0.8, 0.9, 0.95};
// The power stated per load: the interval's half width is below this share of the theory (measured: 0.35%,
// 0.24%, 0.75%, 1.0%, 1.4%, 2.9%, 7.3%); a hash that shifts the mean probes by more is rejected.
constexpr double kResolution[] = {0.01, 0.01, 0.01, 0.015, 0.02, 0.04, 0.08};
const double kAlpha = 1.0 - std::pow(1.0 - 0.001, 1.0 / std::size(kLoads));  // Sidak, per load

FilterConfig GridConfig(std::uint32_t slots = kSlots) {
  FilterConfig config;
  config.lod = false;
  config.cell_size = 1.0f;
  config.jitter_scale = 0.0f;
  config.normal.mode = NormalMode::kNone;
  config.capacity = slots;
  config.probe_limit = slots;
  return config;
}

// `count` records in distinct cells of a 64 x 64 x n grid translated by 4096 r along x: table r's keys.
RecordBatch GridBatch(int table, std::uint32_t count) {
  RecordBatch batch;
  batch.width = count;
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 1.0;
  for (std::uint32_t j = 0; j < count; ++j) {
    VertexSample v;
    v.pixel = j;
    v.position = glm::vec3(float(j % 64 + 4096u * std::uint32_t(table)), float((j / 64) % 64), float(j / 4096)) + 0.5f;
    v.previous = v.position + glm::vec3(0.0f, 0.0f, -1.0f);
    v.contribution = v.throughput = glm::vec3(0.5f);
    batch.records.push_back(MakeVertexRecord(v));
  }
  return batch;
}

using IndexFunction = std::uint32_t (*)(const KeyResult& key);
std::uint32_t TheIndexHash(const KeyResult& key) { return key.slot0; }
std::uint32_t SumOfCoordinates(const KeyResult& key) { return key.words.cell_x + key.words.cell_y + key.words.cell_z; }
std::uint32_t XAlone(const KeyResult& key) { return key.words.cell_x; }

struct LoadVerdict {
  double theory = 0.0, mean = 0.0, half_width = 0.0, p_value = 1.0;
};

LoadVerdict TestLoad(double load, IndexFunction index, std::uint32_t slots = kSlots) {
  const std::uint32_t keys = std::uint32_t(load * slots);
  std::vector<double> means;
  for (int table = 0; table < kTables; ++table) {
    const RecordBatch batch = GridBatch(table, keys);
    const std::vector<KeyResult> results = ComputeKeys(batch.records, MakeKeyParams(GridConfig(slots), 1.0f, keys));
    std::vector<std::uint32_t> slot0s;
    for (const KeyResult& k : results) slot0s.push_back(index(k));
    means.push_back(MeasuredProbesOnHit(slot0s, slots));
  }
  LoadVerdict v;
  v.theory = ExpectedProbesOnHit(slots, keys);
  double sum = 0.0, squares = 0.0;
  for (double m : means) sum += m;
  v.mean = sum / kTables;
  for (double m : means) squares += (m - v.mean) * (m - v.mean);
  const double standard_error = std::sqrt(squares / (kTables - 1) / kTables);
  const boost::math::students_t t(kTables - 1);
  v.half_width = boost::math::quantile(boost::math::complement(t, kAlpha / 2)) * standard_error;
  v.p_value = standard_error > 0.0 ? 2.0 * boost::math::cdf(boost::math::complement(t, std::abs(v.mean - v.theory) / standard_error))
                                   : (v.mean == v.theory ? 1.0 : 0.0);
  return v;
}

// The theory itself, against every hash sequence of small tables enumerated: the exact mean over all M^N
// equally likely sequences of slot0s.
TEST(CollisionStatistics, KnuthsExpectationEqualsEnumerationOfSmallTables) {
  for (std::uint32_t slots : {2u, 4u, 8u}) {
    for (std::uint32_t keys = 1; keys < slots && keys <= 5; ++keys) {
      std::uint64_t sequences = 1;
      for (std::uint32_t k = 0; k < keys; ++k) sequences *= slots;
      double hits = 0.0, misses = 0.0;
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
        for (std::uint32_t s = 0; s < slots; ++s) {  // a search for a key not in the table, from every slot
          for (std::uint32_t slot = s;; slot = (slot + 1) % slots) {
            misses += 1.0 / slots;
            if (!taken[slot]) break;
          }
        }
      }
      EXPECT_NEAR(hits / double(sequences), ExpectedProbesOnHit(slots, keys), 1e-12) << keys << " keys in " << slots << " slots";
      EXPECT_NEAR(misses / double(sequences), ExpectedProbesOnMiss(slots, keys), 1e-12) << keys << " keys in " << slots << " slots";
    }
  }
}

TEST(CollisionStatistics, TheIndexHashProbesAsUniformHashingDoesAtEveryLoad) {
  for (std::size_t l = 0; l < std::size(kLoads); ++l) {
    const double load = kLoads[l];
    const LoadVerdict v = TestLoad(load, TheIndexHash);
    std::printf("load %.2f: mean probes %.4f, theory %.4f (about %.4f), p %.3g, interval +-%.4f\n", load, v.mean, v.theory,
                0.5 * (1.0 + 1.0 / (1.0 - load)), v.p_value, v.half_width);
    EXPECT_GT(v.p_value, kAlpha) << "load " << load << ": mean " << v.mean << ", theory " << v.theory;
    EXPECT_LT(v.half_width, kResolution[l] * v.theory) << "load " << load << ": too little power";
  }
}

TEST(CollisionStatistics, RejectsAClusteringHashAndOneThatDropsWords) {
  for (const IndexFunction alternative : {SumOfCoordinates, XAlone}) {
    for (const double load : kLoads) {
      if (load < 0.5) continue;
      const LoadVerdict v = TestLoad(load, alternative, kSmallSlots);
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
    const FilterConfig config = GridConfig();
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
