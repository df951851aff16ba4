// Temporal integration through the Backend interface (core/backend.h), on all three backends: a table
// kept over K frames holds, in fixed64 and bit for bit, what one frame of all K frames' records gives; with jitter
// (each frame's own random numbers) it is the sum of each frame's table alone. The table checker judges each
// frame from the table before it, and catches a backend that forgets the table between frames.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/backend.h"
#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "emulated/emulated_backend.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_backend.h"
#include "reference/reference_filter.h"
#include "verifier/checker/table_checker.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

using Key = std::array<std::uint32_t, 6>;

struct CellValue {
  std::array<std::uint64_t, 3> sum{};
  std::uint64_t count = 0;
  bool operator==(const CellValue&) const = default;
};
using Cells = std::map<Key, CellValue>;

constexpr std::uint32_t kFrames = 4;
constexpr std::uint32_t kSize = 24;
constexpr std::uint32_t kSpp = 2;

std::vector<RecordBatch> TraceFrames(const std::string& scene) {
  return TracedFrames(LoadScene(scene), kSize, kSpp, kFrames);
}

// All frames' records as one frame: each pixel's samples of frame 0, then of frame 1, ...; the image size (and so
// the footprint of the level of detail) is the frames' own.
RecordBatch AsOneFrame(const std::vector<RecordBatch>& frames) {
  RecordBatch all = frames[0];
  all.samples_per_pixel = kSpp * kFrames;
  all.records.clear();
  for (std::uint32_t pixel = 0; pixel < kSize * kSize; ++pixel) {
    for (const RecordBatch& frame : frames) {
      for (std::uint32_t s = 0; s < kSpp; ++s) all.records.push_back(frame.records[pixel * kSpp + s]);
    }
  }
  return all;
}

Cells CellsOf(const FilterResult& result) {
  Cells cells;
  for (const TableCell& cell : result.cells) cells[cell.key] = {cell.fixed_sum, cell.count};
  return cells;
}

Key KeyOf(const KeyResult& key) {
  const shared::KeyWords& w = key.words;
  return {w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra};
}

// A hashed backend over a sequence: each frame judged by the checker against the table before it; at the end the
// table's slots as cells, keyed by the full key of the records every frame placed there (a slot whose records
// carry two keys fails the test: these tables are uncrowded, with 32-bit fingerprints).
class HashedSequence {
 public:
  template <typename Run>
  void Frame(const RecordBatch& batch, const Run& run, const std::string& what) {
    const std::vector<TableViolation> violations =
        CheckTable({run.table, batch.records, run.keys, run.placements, before_ ? &*before_ : nullptr});
    EXPECT_TRUE(violations.empty()) << what << ": " << violations.front().ToString();
    EXPECT_EQ(run.probe_failures, 0u) << what;
    for (std::size_t i = 0; i < run.placements.size(); ++i) {
      if (run.placements[i] >= run.table.capacity) continue;
      const auto [it, inserted] = key_of_slot_.emplace(run.placements[i], KeyOf(run.keys[i]));
      EXPECT_EQ(it->second, KeyOf(run.keys[i])) << what << ": slot " << run.placements[i] << " aliased";
    }
    before_ = run.table;
  }
  Cells Final() const {
    Cells cells;
    for (const auto& [slot, key] : key_of_slot_) cells[key] = {before_->fixed_sums[slot], before_->counts[slot]};
    return cells;
  }

 private:
  std::optional<HashTableDump> before_;
  std::map<std::uint32_t, Key> key_of_slot_;
};

// Every backend this test runs, each with a name, and how to judge its frames.
struct Sequence {
  std::string name;
  std::unique_ptr<Backend> backend;
};

std::vector<Sequence> AllBackends() {
  std::vector<Sequence> backends;
  backends.push_back({"reference", std::make_unique<ReferenceBackend>()});
  EmulatorOptions fast;
  backends.push_back({"emulated fast", std::make_unique<EmulatedBackend>(fast)});
  EmulatorOptions faithful;
  faithful.mode = simt::Mode::kFaithful;
  faithful.warp_size = 8;
  faithful.schedule = "random:7";
  backends.push_back({"emulated faithful", std::make_unique<EmulatedBackend>(faithful)});
  for (const StagingPolicy staging : kStagingPolicies) {
    backends.push_back(
        {std::string("vulkan, staging ") + ToString(staging), std::make_unique<VulkanBackend>(TestDevice(staging))});
  }
  return backends;
}

// Runs the frames through a backend from an empty table; returns its final table as cells and its last image.
Cells RunSequence(Sequence& s, const std::vector<RecordBatch>& frames, FilterConfig config, Image* last_image) {
  s.backend->Reset();
  HashedSequence hashed;
  for (std::uint32_t k = 0; k < frames.size(); ++k) {
    config.frame = k;
    *last_image = s.backend->FilterFrame(frames[k], config);
    EXPECT_EQ(s.backend->frames_filtered(), k + 1);
    const std::string what = s.name + ", frame " + std::to_string(k);
    if (const HashedRun* run = s.backend->LastHashedRun()) hashed.Frame(frames[k], *run, what);
  }
  if (const FilterResult* exact = s.backend->LastExactResult()) return CellsOf(*exact);
  return hashed.Final();
}

FilterConfig SequenceConfig(const RecordBatch& all) {
  FilterConfig config;
  config.capacity = 1u << 14;
  config.frames = kFrames;
  config.fixed_point_bits = ChooseFixedPointBits(all.records);  // the F one frame of every record chooses
  return config;
}

// Without jitter a record's key does not depend on its frame: K frames integrated are one frame of them all.
TEST(TemporalIntegration, StaticSceneOverKFramesEqualsOneFrameOfAllRecordsOnEveryBackend) {
  const std::vector<RecordBatch> frames = TraceFrames("cornell");
  const RecordBatch all = AsOneFrame(frames);
  FilterConfig config = SequenceConfig(all);
  config.jitter_scale = 0.0f;
  const Cells expected = CellsOf(ReferenceFilter(all, config));
  ASSERT_GT(expected.size(), 100u);
  Image reference_image;
  for (Sequence& s : AllBackends()) {
    Image image;
    const Cells cells = RunSequence(s, frames, config, &image);
    EXPECT_EQ(cells.size(), expected.size()) << s.name;
    EXPECT_TRUE(cells == expected) << s.name << ": the table after " << kFrames
                                   << " frames differs from one frame of all";
    // The last frame resolved against the whole table: the same bits on every backend (nothing failed or aliased).
    if (s.name == "reference") reference_image = image;
    EXPECT_TRUE(image.pixels == reference_image.pixels)
        << s.name << ": last frame's image differs from the reference's";
  }
}

// With jitter each frame keys its records with its own random numbers: the table is the sum of each frame's own.
TEST(TemporalIntegration, WithJitterTheTableIsTheSumOfEachFramesTableOnEveryBackend) {
  const std::vector<RecordBatch> frames = TraceFrames("cornell");
  FilterConfig config = SequenceConfig(AsOneFrame(frames));
  ASSERT_GT(config.jitter_scale, 0.0f);
  Cells expected;
  for (std::uint32_t k = 0; k < kFrames; ++k) {
    FilterConfig alone = config;
    alone.frame = k;
    for (const auto& [key, value] : CellsOf(ReferenceFilter(frames[k], alone))) {
      CellValue& sum = expected[key];
      for (int c = 0; c < 3; ++c) sum.sum[c] += value.sum[c];
      sum.count += value.count;
    }
  }
  for (Sequence& s : AllBackends()) {
    Image image;
    EXPECT_TRUE(RunSequence(s, frames, config, &image) == expected) << s.name;
  }
}

// A backend that forgets the table between frames passes the checker frame by frame alone, and fails it when the
// checker is given the table before the frame; the right table passes only with it.
TEST(TemporalIntegration, TheCheckerJudgesAFrameFromTheTableBeforeIt) {
  const std::vector<RecordBatch> frames = TraceFrames("cornell");
  FilterConfig config = SequenceConfig(AsOneFrame(frames));
  EmulatedBackend backend{EmulatorOptions{}};
  backend.FilterFrame(frames[0], config);
  const EmulatedRun first = backend.run();
  config.frame = 1;
  backend.FilterFrame(frames[1], config);
  const EmulatedRun& second = backend.run();
  EXPECT_TRUE(CheckTable({second.table, frames[1].records, second.keys, second.placements, &first.table}).empty());
  EXPECT_FALSE(CheckTable({second.table, frames[1].records, second.keys, second.placements}).empty())
      << "the second frame's table holds the first frame's records too";

  const EmulatedRun forgetful = EmulatedFilter(frames[1], config, EmulatorOptions{}, AccumulateKernel, nullptr);
  std::map<TableInvariant, int> seen;
  for (const TableViolation& v :
       CheckTable({forgetful.table, frames[1].records, forgetful.keys, forgetful.placements, &first.table})) {
    ++seen[v.invariant];
  }
  EXPECT_GT(seen[TableInvariant::kTagChangedAcrossFrames] + seen[TableInvariant::kCountMismatch], 0);
  EXPECT_GT(seen[TableInvariant::kTotalMismatch], 0);
}

// Nothing that shapes the table or the keys may change within a sequence; Reset starts a new one.
TEST(TemporalIntegration, ASequenceRefusesAChangedTableUntilReset) {
  const std::vector<RecordBatch> frames = TraceFrames("cornell-tiny");
  FilterConfig config;
  config.capacity = 1u << 12;
  for (Sequence& s : AllBackends()) {
    s.backend->FilterFrame(frames[0], config);
    FilterConfig changed = config;
    changed.capacity = 1u << 13;
    try {
      s.backend->FilterFrame(frames[1], changed);
      ADD_FAILURE() << s.name << ": a changed capacity went into the same table";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("--capacity"), std::string::npos) << e.what();
    }
    EXPECT_EQ(s.backend->frames_filtered(), 1u);
    s.backend->Reset();
    s.backend->FilterFrame(frames[1], changed);
    EXPECT_EQ(s.backend->frames_filtered(), 1u) << s.name;
  }
}

}  // namespace
}  // namespace hpsf::testing
