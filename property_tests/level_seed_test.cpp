// Resolution changes across frames (core/level_seed.h, Binder et al. §3.4.2) on all three backends: a cell
// new at a coarser level is seeded with its children's sums and counts, one new at a finer level with its parent's
// share, the same way in the reference (exact keys), the emulator and Vulkan (the table before the frame, looked up
// by fingerprint); the table checker recomputes every seed from the table before the frame, and the contract holds
// over a moving camera whose levels change.

#include "core/level_seed.h"

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/footprint.h"
#include "core/shared/level_seed.h"
#include "property_tests/hashed_backends.h"
#include "property_tests/traced_batch.h"
#include "reference/reference_backend.h"
#include "tracer/scene_file.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/contract_levels.h"

namespace hpsf::testing {
namespace {

TEST(LevelSeed, ParsesAndNeedsLevelOfDetail) {
  EXPECT_EQ(ParseLevelSeed("none"), LevelSeed{});
  EXPECT_EQ(ParseLevelSeed("seed"), (LevelSeed{true, 0}));
  EXPECT_EQ(ParseLevelSeed("seed:3").ToString(), "seed:3");
  for (const char* bad : {"seed:", "seed:17", "seed:-1", "seeds", ""}) {
    try {
      ParseLevelSeed(bad);
      ADD_FAILURE() << bad << " parsed";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--level-change: ", 0), 0u) << e.what();
    }
  }
  FilterConfig config;
  config.level_seed = ParseLevelSeed("seed");
  config.lod = false;
  EXPECT_THROW(config.Validate(), ConfigError);
  // The parent of a cell holds its points; its children tile it.
  const shared::KeyWords cell{std::uint32_t(-3), 4, std::uint32_t(-1), 100, 0, 0};
  const shared::KeyWords parent = shared::ParentKeyWords(cell);
  EXPECT_EQ(int(parent.cell_x), -2);  // floor(-3 / 2)
  EXPECT_EQ(int(parent.cell_y), 2);
  EXPECT_EQ(int(parent.cell_z), -1);
  EXPECT_EQ(parent.level, 101u);
  for (std::uint32_t child = 0; child < shared::kLevelSeedChildren; ++child) {
    const shared::KeyWords back = shared::ParentKeyWords(shared::ChildKeyWords(cell, child));
    EXPECT_EQ(back.cell_x, cell.cell_x);
    EXPECT_EQ(back.cell_y, cell.cell_y);
    EXPECT_EQ(back.cell_z, cell.cell_z);
    EXPECT_EQ(back.level, cell.level);
  }
}

// Records at the centres of cells of edge 2^level: a vertex seen from distance d has the level of footprint * d.
struct Placed {
  glm::ivec3 cell;
  int level;
};

RecordBatch BatchAt(const std::vector<Placed>& records, std::uint32_t frame) {
  RecordBatch batch;
  batch.width = static_cast<std::uint32_t>(records.size());
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 0.5;
  batch.frame = frame;
  // The distance that gives each level: footprint * d = 1.5 * 2^level, inside the level's octave.
  const float footprint = FootprintScale(FilterConfig{}.filter_width_px, batch.fov_y_radians, batch.height);
  for (std::uint32_t i = 0; i < records.size(); ++i) {
    const float edge = std::ldexp(1.0f, records[i].level);
    VertexSample v;
    v.pixel = i;
    v.position = (glm::vec3(records[i].cell) + glm::vec3(0.5f)) * edge;
    v.previous = v.position + glm::vec3(0.0f, 0.0f, -1.5f * edge / footprint);
    v.contribution = glm::vec3(1.0f + 0.25f * float(i % 7), 0.5f, 0.125f * float(1 + i % 3));
    v.throughput = glm::vec3(0.5f);
    batch.records.push_back(MakeVertexRecord(v));
  }
  return batch;
}

// Frame 0: two records in each of the 8 children (level 1) of P = (5, 3, -7) at level 2. Frame 1: P itself, new at
// the coarser level, is seeded with its children (count 16), and Q = (6, 3, -7) at level 2 gets 16 records and no
// seed. Frame 2: a child of Q, new at the finer level and with no children of its own, is seeded with Q's share (16
// >> 3 = 2). On every backend each frame passes the checker, every record's slot holds its reference cell's count
// and sums bit for bit (fixed64, and packed-decimal's words), and the seeds counted are those; without seeding
// nothing is seeded.
TEST(LevelSeed, ACellNewAtAnotherLevelStartsFromItsChildrenOrItsParent) {
  const glm::ivec3 p(5, 3, -7), q(6, 3, -7);
  std::vector<Placed> frame0, frame1, frame2;
  for (int child = 0; child < 8; ++child) {
    const glm::ivec3 c = 2 * p + glm::ivec3(child & 1, (child >> 1) & 1, child >> 2);
    frame0.push_back({c, 1});
    frame0.push_back({c, 1});
  }
  for (int k = 0; k < 3; ++k) frame1.push_back({p, 2});
  for (int k = 0; k < 16; ++k) frame1.push_back({q, 2});
  for (int k = 0; k < 2; ++k) frame2.push_back({2 * q + glm::ivec3(1, 0, 1), 1});
  const std::vector<RecordBatch> frames = {BatchAt(frame0, 0), BatchAt(frame1, 1), BatchAt(frame2, 2)};
  const std::vector<std::uint64_t> expected_seeds = {0, 1, 1};
  // Record 0's cell after each frame, with and without the seed.
  const std::vector<std::uint64_t> seeded_counts = {2, 3 + 16, 2 + 2}, unseeded_counts = {2, 3, 2};

  for (const auto& [accumulation, mode] :
       {std::pair{Accumulation::kFixed64, "seed"}, std::pair{Accumulation::kFixed64, "none"},
        std::pair{Accumulation::kPackedDecimal, "seed"}}) {
    FilterConfig config;
    config.accumulation = accumulation;
    config.capacity = 1024;
    config.jitter_scale = 0.0f;
    config.frames = 3;
    config.level_seed = ParseLevelSeed(mode);
    const bool seeding = config.level_seed.enabled;
    for (HashedBackend& hashed : HashedBackends()) {
      ReferenceBackend reference;
      std::optional<HashTableDump> before;
      for (std::uint32_t k = 0; k < frames.size(); ++k) {
        config.frame = k;
        const std::string what =
            hashed.name + ", " + ToString(accumulation) + ", " + mode + ", frame " + std::to_string(k);
        reference.FilterFrame(frames[k], config);
        hashed.backend->FilterFrame(frames[k], config);
        const HashedRun& run = RunOf(*hashed.backend);
        ASSERT_EQ(run.keys[0].level, k == 1 ? 2 : 1) << what << ": the constructed level";
        TableCheckInput input{run.table, frames[k].records, run.keys, run.placements, before ? &*before : nullptr};
        input.frame = k;
        input.level_seed = config.level_seed;
        const std::vector<TableViolation> violations = CheckTable(input);
        EXPECT_TRUE(violations.empty()) << what << ": " << violations.front().ToString();
        EXPECT_EQ(run.seeded, seeding ? expected_seeds[k] : 0u) << what;
        EXPECT_EQ(reference.result().stats.cells_seeded, seeding ? expected_seeds[k] : 0u) << what;
        const FilterResult& exact = reference.result();
        for (std::uint32_t i = 0; i < frames[k].records.size(); ++i) {
          const TableCell& cell = exact.cells[exact.placement[i]];
          ASSERT_LT(run.placements[i], config.capacity) << what;
          EXPECT_EQ(run.table.counts[run.placements[i]], cell.count) << what << ", record " << i;
          EXPECT_EQ(run.table.fixed_sums[run.placements[i]], cell.fixed_sum) << what << ", record " << i;
        }
        const std::uint64_t count = run.table.counts[run.placements[0]];
        EXPECT_EQ(count, seeding ? seeded_counts[k] : unseeded_counts[k]) << what;
        before = run.table;
      }
    }
  }
}

// The Cornell box with the camera dollying in (cornell-dolly.json: every location moves down a level) over 6 frames,
// in each accumulation, with seeding: the contract holds on the emulator and Vulkan (the checker recomputing every
// seed at level 2, the reference's exact seeds at level 3), cells were seeded, as many as the reference seeded.
TEST(LevelSeed, TheContractHoldsOverACameraDollyingIn) {
  constexpr std::uint32_t kFrames = 6;
  const std::vector<RecordBatch> frames =
      TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-dolly.json"), 24, 2, kFrames);
  std::vector<std::uint32_t> numbers;
  for (const RecordBatch& frame : frames) numbers.push_back(frame.frame);
  for (const Accumulation accumulation :
       {Accumulation::kFixed64, Accumulation::kFloat32, Accumulation::kPackedDecimal}) {
    FilterConfig config;
    config.capacity = 4096;
    config.frames = kFrames;
    config.accumulation = accumulation;
    config.level_seed = ParseLevelSeed("seed:1");
    EmulatedBackend emulated({}), emulated_rerun({});
    VulkanBackend vulkan(TestDevice(StagingPolicy::kNever)), vulkan_rerun(TestDevice(StagingPolicy::kNever));
    const JudgedBackend judged[] = {{"emulated", &emulated, &emulated_rerun, "rerun", false, false},
                                    {"vulkan", &vulkan, &vulkan_rerun, "rerun", false, true}};
    const CrosscheckReport report = JudgeSequence(frames, numbers, config, judged);
    EXPECT_TRUE(report.Passed()) << ToString(accumulation) << ": " << report.FirstFailure();
    // The last frame's seeds, on each backend and in the reference.
    ReferenceBackend reference;
    std::uint64_t seeded_reference = 0, seeded_emulated = 0;
    EmulatedBackend counted({});
    for (std::uint32_t k = 0; k < kFrames; ++k) {
      config.frame = numbers[k];
      reference.FilterFrame(frames[k], config);
      counted.FilterFrame(frames[k], config);
      seeded_reference += reference.result().stats.cells_seeded;
      seeded_emulated += RunOf(counted).seeded;
    }
    std::printf("%s: cells seeded over %u frames: reference %llu, emulated %llu\n", ToString(accumulation).c_str(),
                kFrames, (unsigned long long)seeded_reference, (unsigned long long)seeded_emulated);
    EXPECT_GT(seeded_reference, 50u);
    EXPECT_EQ(seeded_emulated, seeded_reference);
  }
}

}  // namespace
}  // namespace hpsf::testing
