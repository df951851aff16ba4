// The probing schemes (core/shared/probe_scheme.h) under the contract: every scheme passes on all three backends
// on the built-in scenes, one frame and sequences, roomy and crowded; the checker judges a table by the scheme it
// was declared with (a table right under one scheme is wrong under another, placement by placement and tombstone
// by tombstone).

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/eviction.h"
#include "core/temporal.h"
#include "emulated/emulated_filter.h"
#include "property_tests/constructed_cells.h"
#include "property_tests/crosscheck_report_figures.h"
#include "property_tests/hashed_backends.h"
#include "property_tests/traced_batch.h"
#include "tracer/scene_file.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/crosscheck.h"

namespace hpsf::testing {
namespace {

const std::vector<std::string> kAllBackends = {"reference", "emulated", "vulkan"};

struct Scheme {
  ProbeKind kind;
  std::uint32_t size;
  std::string Name() const { return ToString(kind) + ":" + std::to_string(size); }
};

FilterConfig Roomy(const Scheme& scheme) {
  FilterConfig config;
  config.capacity = 1u << 12;
  config.probing = scheme.kind;
  config.probe_limit = scheme.size;
  return config;
}

// A table smaller than a frame's cells (the Cornell box at 32x32 has about 600, the furnace about 300), 8-bit
// fingerprints: probe failures and aliases in every frame.
FilterConfig Crowded(const Scheme& scheme) {
  FilterConfig config = Roomy(scheme);
  config.capacity = 256;
  config.fingerprint_bits = 8;
  return config;
}

std::set<TableInvariant> Invariants(const std::vector<TableViolation>& violations) {
  std::set<TableInvariant> invariants;
  for (const TableViolation& v : violations) invariants.insert(v.invariant);
  return invariants;
}

TEST(ProbingSchemes, EverySchemePassesTheContractOnAllThreeBackendsInOneFrame) {
  Crosschecker checker(kAllBackends);
  for (const char* scene : {"cornell", "furnace"}) {
    const RecordBatch batch = TracedBatch(scene, 32, 2);
    for (const Scheme& scheme : {Scheme{ProbeKind::kBucket, 16}, Scheme{ProbeKind::kBucketWindow, 16},
                                 Scheme{ProbeKind::kBucket, 4}, Scheme{ProbeKind::kBucketWindow, 4}}) {
      for (const bool crowded : {false, true}) {
        for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
          FilterConfig config = crowded ? Crowded(scheme) : Roomy(scheme);
          config.accumulation = accumulation;
          const std::string name = std::string(scene) + ", " + scheme.Name() + (crowded ? ", crowded, " : ", roomy, ") +
                                   ToString(accumulation);
          const CrosscheckReport report = checker.Check(batch, config, EmulatorOptions{});
          EXPECT_TRUE(report.Passed()) << name << ": " << report.FirstFailure();
          for (int level = 1; level <= 4; ++level) EXPECT_TRUE(Level(report, level).applicable) << name;
          if (crowded) {
            for (const QualityFigures& q : report.quality) {
              if (q.backend != "reference") {
                EXPECT_GT(q.probe_failures, 0u) << name << ", " << q.backend;
              }
            }
          }
        }
      }
    }
  }
}

// Four frames of the animated Cornell box through one table: each scheme under age eviction with a blend, and under
// priority eviction in a crowded table (the tombstones an insertion may claim lie in the scheme's candidates).
TEST(ProbingSchemes, EverySchemePassesTheContractOnAllThreeBackendsOverFrames) {
  constexpr std::uint32_t kFrames = 4;
  const std::vector<RecordBatch> frames =
      TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-animated.json"), 24, 2, kFrames);
  Crosschecker checker(kAllBackends);
  for (const Scheme& scheme : {Scheme{ProbeKind::kBucket, 8}, Scheme{ProbeKind::kBucketWindow, 8}}) {
    for (const char* eviction : {"strict", "stale:2", "priority"}) {
      FilterConfig config = std::string(eviction) == "priority" ? Crowded(scheme) : Roomy(scheme);
      if (std::string(eviction) == "strict") config.capacity = 512;  // tombstones crowd the buckets
      config.frames = kFrames;
      config.eviction = ParseEviction(eviction);
      config.temporal = ParseTemporal(std::string(eviction) == "stale:2" ? "adaptive" : "ema:0.5");
      EmulatorOptions emulator;
      emulator.mode = simt::Mode::kFaithful;
      emulator.warp_size = 8;
      emulator.schedule = "random:3";
      const std::string name = scheme.Name() + ", " + eviction + ", capacity " + std::to_string(config.capacity);
      const CrosscheckReport report = checker.CheckFrames(frames, config, emulator);
      EXPECT_TRUE(report.Passed()) << name << ": " << report.FirstFailure();
      EXPECT_EQ(report.frames, kFrames) << name;
      EXPECT_NE(Level(report, 1).note.find("compared over 4 frames"), std::string::npos) << name;
    }
  }
}

// A crowded bucket table holds records before their home slot (the bucket starts below it), which linear probing
// never does: the checker accepts them under the scheme the table declares and names them under the other. And a
// linear table whose windows wrap past the last slot is wrong as a bucket-window table, which never wraps.
TEST(ProbingSchemes, TheCheckerJudgesATableByItsDeclaredScheme) {
  const RecordBatch batch = TracedBatch("cornell", 32, 2);
  FilterConfig bucket = Crowded({ProbeKind::kBucket, 8});
  const EmulatedRun run = EmulatedFilter(batch, bucket, EmulatorOptions{});
  EXPECT_TRUE(CheckTable({run.table, batch.records, run.keys, run.placements}).empty());
  std::uint32_t before_home = 0;
  for (std::uint32_t i = 0; i < run.placements.size(); ++i) {
    before_home += run.placements[i] < bucket.capacity && run.placements[i] < run.keys[i].slot0;
  }
  ASSERT_GT(before_home, 0u);
  HashTableDump as_linear = run.table;
  as_linear.probing = ProbeKind::kLinear;
  std::uint32_t outside = 0;
  for (const TableViolation& v : CheckTable({as_linear, batch.records, run.keys, run.placements}))
    outside += v.invariant == TableInvariant::kSlotOutsideWindow;
  EXPECT_EQ(outside, before_home);

  FilterConfig linear = Crowded({ProbeKind::kLinear, 8});
  const EmulatedRun wrapped = EmulatedFilter(batch, linear, EmulatorOptions{});
  HashTableDump as_window = wrapped.table;
  as_window.probing = ProbeKind::kBucketWindow;
  std::uint32_t wrapping = 0;
  for (std::uint32_t i = 0; i < wrapped.placements.size(); ++i) {
    wrapping += wrapped.placements[i] < linear.capacity && wrapped.placements[i] < wrapped.keys[i].slot0;
  }
  ASSERT_GT(wrapping, 0u);
  EXPECT_TRUE(Invariants(CheckTable({as_window, batch.records, wrapped.keys, wrapped.placements}))
                  .contains(TableInvariant::kSlotOutsideWindow));

  // A home slot past the table (a key a shader or a corruption left) is named, never walked: under buckets no mask
  // brings it back into the table (fuzz_checker found the checker reading past its arrays).
  std::vector<KeyResult> keys = run.keys;
  for (std::uint32_t i = 0; i < keys.size(); ++i) {
    if (run.placements[i] == kProbeFailure) {
      keys[i].slot0 = bucket.capacity + 4;
      const std::vector<TableViolation> v = CheckTable({run.table, batch.records, keys, run.placements});
      ASSERT_FALSE(v.empty());
      EXPECT_NE(v.front().ToString().find("slot0 260 is not below the capacity 256"), std::string::npos)
          << v.front().ToString();
      break;
    }
  }
}

// Four cells share home slot 0 and fill slots 0 to 3 (in the order their atomics land), B's home is slot 4. Frame 1
// repeats all but the cell in slot 3, which strict eviction makes a tombstone. Linear probing keeps it (B, live at
// slot 4, is in the window of a key whose home is slot 1, 2 or 3); buckets of 4 empty it (no bucket holds slots 3
// and 4). Each backend does what its scheme says, and the checker blames each outcome under the other scheme.
TEST(ProbingSchemes, ATombstoneIsKeptExactlyWhenALaterSlotOfItsSchemeIsLive) {
  auto config_of = [](ProbeKind kind) {
    FilterConfig c = ConstructedConfig(8, 4);
    c.probing = kind;
    c.frames = 2;
    c.eviction = ParseEviction("strict");
    return c;
  };
  const FilterConfig linear = config_of(ProbeKind::kLinear);
  std::vector<glm::ivec3> home0;
  int x = 0;
  while (home0.size() < 4) {
    home0.push_back(FindCell(
        linear, [](const KeyResult& k) { return k.slot0 == 0u; }, x));
    x = home0.back().x + 1;
  }
  const glm::ivec3 b = FindCell(linear, [](const KeyResult& k) { return k.slot0 == 4u; });
  const RecordBatch frame0 = BatchOfCells({home0[0], home0[1], home0[2], home0[3], b});

  for (const ProbeKind kind : {ProbeKind::kLinear, ProbeKind::kBucket}) {
    const FilterConfig config = config_of(kind);
    const bool kept = kind == ProbeKind::kLinear;
    for (HashedBackend& h : HashedBackends()) {
      const std::string name = ToString(kind) + ", " + h.name;
      FilterConfig c = config;
      c.frame = 0;
      h.backend->FilterFrame(frame0, c);
      const HashTableDump first = RunOf(*h.backend).table;
      ASSERT_EQ(first.tags[4], KeyOfCell(config, b).fingerprint) << name;
      std::vector<glm::ivec3> survivors = {b};
      for (const glm::ivec3& cell : home0) {
        if (KeyOfCell(config, cell).fingerprint != first.tags[3]) survivors.push_back(cell);
      }
      ASSERT_EQ(survivors.size(), 4u) << name << ": slot 3 holds none of the four cells";
      RecordBatch frame1 = BatchOfCells(survivors);
      frame1.frame = 1;
      c.frame = 1;
      h.backend->FilterFrame(frame1, c);
      const HashedRun& second = RunOf(*h.backend);
      EXPECT_EQ(second.table.tags[3] != kEmptyTag, kept) << name;
      EXPECT_EQ(second.table.counts[3], 0u) << name;
      const TableCheckInput right{
          second.table, frame1.records, second.keys, second.placements, &first, config.eviction, 1};
      EXPECT_TRUE(CheckTable(right).empty()) << name;
      HashTableDump other = second.table, other_before = first;
      other.probing = other_before.probing = kept ? ProbeKind::kBucket : ProbeKind::kLinear;
      const TableCheckInput wrong{other, frame1.records, second.keys, second.placements, &other_before, config.eviction,
                                  1};
      EXPECT_EQ(Invariants(CheckTable(wrong)),
                std::set<TableInvariant>{kept ? TableInvariant::kTombstoneKept : TableInvariant::kHoleBeforeLiveSlot})
          << name;
    }
  }
}

}  // namespace
}  // namespace hpsf::testing
