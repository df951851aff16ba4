// The neighbourhood search (--neighbour-search; core/shared/neighbour_search.h; Binder et al. §3.3.1): the stencil's
// side follows floor at negative coordinates and nests across levels; a lookup passes tombstones and stops at an empty
// slot; every backend reads exactly the cells a brute-force oracle reads and agrees with the reference on scenes,
// sequences with eviction, roomy and crowded tables; a lookup that aliases is classified, not blamed; with no cell
// below the threshold the search changes no bit; and the broken variants (a lookup that claims, one that stops at a
// tombstone, a stencil side by truncation, in the emulator and as a shader) fail the contract. Label `levels`.

#include "core/shared/neighbour_search.h"

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/effect_plan.h"
#include "core/error.h"
#include "core/shared/eviction_priority.h"
#include "core/shared/lookup.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_backend.h"
#include "emulated/emulated_filter.h"
#include "property_tests/constructed_cells.h"
#include "property_tests/crosscheck_report_figures.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_filter.h"
#include "verifier/contract/crosscheck.h"
#include "vulkan/vulkan_filter.h"

namespace hpsf::testing {
namespace {

const std::vector<std::string> kAllBackends = {"reference", "emulated", "vulkan"};

shared::KeyPosition PositionAt(glm::vec3 p, float inverse_size = 1.0f) {
  shared::KeyPosition at;
  at.jittered = p;
  at.level = 0;
  at.inverse_size = inverse_size;
  return at;
}

// The side is the half of the cell by floor: -0.3 lies in cell -1 at 0.7, the upper half; -0.7 at 0.3, the lower.
TEST(NeighbourSearch, TheSideIsTheHalfOfTheCellByFloorAtNegativeCoordinates) {
  EXPECT_EQ(shared::StencilSidesAtOwnLevel(PositionAt({0.25f, 0.75f, 0.5f})), glm::uvec3(0, 1, 1));
  EXPECT_EQ(shared::StencilSidesAtOwnLevel(PositionAt({-0.3f, -0.7f, -1.5f})), glm::uvec3(1, 0, 1));
  EXPECT_EQ(shared::StencilSidesAtOwnLevel(PositionAt({-1e6f - 0.25f, 3e6f + 0.75f, -2.0f})), glm::uvec3(1, 1, 0));
  // Corners: bit a moves along axis a, towards the side.
  const shared::KeyWords cell{uint(-1), 4, 7, 254, 0, 0};
  const glm::uvec3 sides(1, 0, 1);
  EXPECT_EQ(shared::StencilCellWords(cell, sides, 0).cell_x, uint(-1));
  EXPECT_EQ(shared::StencilCellWords(cell, sides, 1).cell_x, 0u);
  EXPECT_EQ(shared::StencilCellWords(cell, sides, 2).cell_y, 3u);
  EXPECT_EQ(shared::StencilCellWords(cell, sides, 4).cell_z, 8u);
  const shared::KeyWords far = shared::StencilCellWords(cell, sides, 7);
  EXPECT_EQ(glm::uvec3(far.cell_x, far.cell_y, far.cell_z), glm::uvec3(0, 3, 8));
}

// k levels up, the side read from the own cell's words is the side of the position in the coarser cell, which
// floor(q 2^-k) holds: checked over positions on both sides of zero at every level.
TEST(NeighbourSearch, TheSideAtACoarserLevelIsThePositionsInThatCell) {
  for (int step = -4000; step <= 4000; ++step) {
    const glm::vec3 p(float(step) * 0.0371f, float(-step) * 0.113f + 0.01f, float(step % 97) * 0.61f);
    const shared::KeyPosition at = PositionAt(p);
    const glm::ivec3 own(glm::floor(p));
    const shared::KeyWords words{uint(own.x), uint(own.y), uint(own.z), 254, 0, 0};
    for (std::uint32_t k = 1; k < shared::kMaxLevels; ++k) {
      const glm::uvec3 expected = shared::StencilSidesAtOwnLevel(PositionAt(p, std::ldexp(1.0f, -int(k))));
      ASSERT_EQ(shared::StencilSidesAtLevel(shared::StencilSidesAtOwnLevel(at), words, k), expected)
          << "position " << p.x << " " << p.y << " " << p.z << ", " << k << " levels up";
    }
  }
}

// A lookup ends at an empty slot, passes a tombstone, another identity and its own identity without samples.
TEST(NeighbourSearch, ALookupPassesTombstonesAndEndsAtAnEmptySlot) {
  EXPECT_EQ(shared::LookupStep(0, 77, 0), shared::kLookupEnd);
  EXPECT_EQ(shared::LookupStep(shared::kTombstoneTag, 77, 0), shared::kLookupNext);
  EXPECT_EQ(shared::LookupStep(78, 77, 3), shared::kLookupNext);
  EXPECT_EQ(shared::LookupStep(77, 77, 0), shared::kLookupNext);
  EXPECT_EQ(shared::LookupStep(77, 77, 3), shared::kLookupFound);
}

// Records at chosen points of unit cells (no jitter, level of detail off), on both sides of zero. The oracle: a
// record whose cell holds fewer than min_count records averages every record of the 2^3 cells nearest its point
// (per axis its cell and the neighbour on the side of the centre the point lies on, by floor), found by brute force
// over the points; others average their cell. Contributions are multiples of 2^-3, so sums are exact and every
// backend's pixel is the oracle's, bit for bit.
TEST(NeighbourSearch, EveryBackendReadsTheCellsABruteForceOracleReads) {
  const std::vector<glm::vec3> points = {
      {0.25f, 0.25f, 0.25f}, {-0.3f, 0.6f, 0.2f},    {-0.7f, 0.4f, 0.9f},   {-0.2f, 0.1f, 0.1f},  {-0.9f, 0.9f, 0.9f},
      {1.2f, 0.3f, 0.3f},    {1.4f, 0.2f, 0.6f},     {0.75f, -0.25f, 0.5f}, {0.6f, -0.6f, -0.6f}, {-1.6f, -1.3f, -0.1f},
      {-1.1f, -0.8f, -0.4f}, {-0.45f, -0.55f, 0.8f}, {0.1f, 1.9f, 0.45f},   {0.3f, 1.2f, 0.55f},  {-2.5f, 0.5f, 0.5f}};
  const RecordBatch batch = BatchAtPoints(points);
  FilterConfig config = ConstructedConfig(1u << 10, 16);
  config.neighbour_search = true;
  VulkanFilter vulkan_filter(TestDevice(StagingPolicy::kNever));
  for (const std::uint32_t min_count : {2u, 3u}) {
    config.min_count = min_count;
    std::map<std::array<int, 3>, std::vector<std::size_t>> members;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const glm::ivec3 c(glm::floor(points[i]));
      members[{c.x, c.y, c.z}].push_back(i);
    }
    std::vector<float> expected(points.size());
    std::uint64_t searching = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const glm::ivec3 c(glm::floor(points[i]));
      const glm::vec3 fraction = points[i] - glm::floor(points[i]);
      const bool search = members[{c.x, c.y, c.z}].size() < min_count;
      searching += search;
      double sum = 0.0, count = 0.0;
      for (int corner = 0; corner < (search ? 8 : 1); ++corner) {
        std::array<int, 3> cell = {c.x, c.y, c.z};
        for (int a = 0; a < 3; ++a) {
          if (corner & (1 << a)) cell[a] += fraction[a] >= 0.5f ? 1 : -1;
        }
        for (const std::size_t j : members[cell]) {
          sum += batch.records[j].contribution.x;
          count += 1.0;
        }
      }
      expected[i] = float(0.5 * (sum / count));
    }
    const FilterResult reference = ReferenceFilter(batch, config);
    const EmulatedRun emulated = EmulatedFilter(batch, config, EmulatorOptions{});
    const VulkanRun vulkan = vulkan_filter.Run(batch, config);
    EXPECT_EQ(reference.stats.records_searched, searching) << min_count;
    EXPECT_EQ(emulated.records_searched, searching) << min_count;
    EXPECT_EQ(vulkan.records_searched, searching) << min_count;
    EXPECT_GT(reference.stats.neighbours_read, 0u);
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_EQ(reference.image.pixels[i].x, expected[i]) << "reference, record " << i << ", min-count " << min_count;
      EXPECT_EQ(emulated.image.pixels[i].x, expected[i]) << "emulated, record " << i << ", min-count " << min_count;
      EXPECT_EQ(vulkan.image.pixels[i].x, expected[i]) << "vulkan, record " << i << ", min-count " << min_count;
    }
  }
}

// The Cornell box and the furnace, and three frames of the dolly with blending and stale eviction, roomy and crowded
// (probe failures and 8-bit aliases), in each accumulation, alone and over two levels: every level of the contract
// passes on all three backends, and records searched. Roomy fixed64 holds nothing classified, so level 3 held every
// image to the reference's, bit for bit.
TEST(NeighbourSearch, EveryBackendAgreesWithTheReferenceOnEveryScene) {
  const std::vector<RecordBatch> cornell = {TracedBatch("cornell", 24, 2)};
  const std::vector<RecordBatch> furnace = {TracedBatch(HPSF_SCENES_DIR "/furnace.json", 24, 2)};
  const std::vector<RecordBatch> dolly = TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-dolly.json"), 24, 1, 3);
  Crosschecker checker(kAllBackends);
  struct Scene {
    const char* name;
    const std::vector<RecordBatch>* frames;
  };
  for (const Scene& scene : {Scene{"cornell", &cornell}, Scene{"furnace", &furnace}, Scene{"dolly", &dolly}}) {
    for (const bool crowded : {false, true}) {
      for (const Accumulation accumulation :
           {Accumulation::kFixed64, Accumulation::kFloat32, Accumulation::kPackedDecimal}) {
        for (const std::uint32_t levels : {1u, 2u}) {
          FilterConfig config;
          config.levels = levels;
          config.min_count = 4;
          config.neighbour_search = true;
          config.accumulation = accumulation;
          config.capacity = crowded ? 1u << 8 : 1u << 14;
          config.probe_limit = crowded ? 4 : 16;
          config.fingerprint_bits = crowded ? 8 : 32;
          config.frames = std::uint32_t(scene.frames->size());
          if (config.frames > 1) {
            config.temporal = ParseTemporal("ema:0.5");
            config.eviction = ParseEviction("stale:1");
          }
          const std::string name = std::string(scene.name) + (crowded ? ", crowded, " : ", roomy, ") +
                                   ToString(accumulation) + ", levels " + std::to_string(levels);
          const CrosscheckReport report = checker.CheckFrames(*scene.frames, config, EmulatorOptions{});
          EXPECT_TRUE(report.Passed()) << name << ": " << report.FirstFailure();
          for (const char* backend : {"emulated", "vulkan"}) {
            const QualityFigures& q = QualityOf(report, backend);
            if (crowded) {
              EXPECT_GT(q.probe_failures + q.aliased_slots, 0u) << name << ", " << backend << ": nothing crowded";
            } else {
              EXPECT_EQ(q.probe_failures + q.aliased_slots + q.classified_searches, 0u) << name << ", " << backend;
            }
          }
        }
      }
    }
  }
  FilterConfig config;
  config.min_count = 4;
  config.neighbour_search = true;
  EXPECT_GT(ReferenceFilter(cornell[0], config).stats.records_searched, cornell[0].records.size() / 10);
}

// A lookup for a neighbour no record keyed can find a live cell whose 8-bit fingerprint is the same in its window:
// the record reads another cell, which the reference does not. Over jitter seeds of a small Cornell box in a crowded
// table the contract passes on every one, and on some no slot aliased and no probe failed, yet searches were
// classified: for their lookups alone.
TEST(NeighbourSearch, ALookupThatAliasesIsClassifiedNotBlamed) {
  const std::vector<RecordBatch> frames = {TracedBatch("cornell", 48, 1)};
  FilterConfig config;
  config.min_count = 4;
  config.neighbour_search = true;
  config.capacity = 4096;
  config.probe_limit = 64;
  config.fingerprint_bits = 8;
  Crosschecker checker(kAllBackends);
  int lookups_alone = 0;
  for (std::uint32_t seed = 1; seed <= 8; ++seed) {
    config.seed = seed;
    const CrosscheckReport report = checker.CheckFrames(frames, config, EmulatorOptions{});
    EXPECT_TRUE(report.Passed()) << "seed " << seed << ": " << report.FirstFailure();
    for (const char* backend : {"emulated", "vulkan"}) {
      const QualityFigures& q = QualityOf(report, backend);
      lookups_alone += q.aliased_slots + q.probe_failures == 0 && q.classified_searches > 0;
    }
  }
  EXPECT_GT(lookups_alone, 0);
}

// Effect planning: the search runs only for a record whose chosen cell is below the threshold. Over eight levels
// with a threshold of 2 every record's coarsest level holds more, so none searches, and the image is the one
// without the search, bit for bit, on every backend. Forced (--force-effect neighbour-search), every pixel goes
// through the search pass, Vulkan's second among them: the same bits, with no record below the threshold and with
// about two fifths of them below it (448 of 1,152 in the reference).
TEST(NeighbourSearch, WithNoCellBelowTheThresholdTheSearchChangesNoBit) {
  const RecordBatch batch = TracedBatch("cornell", 24, 2);
  FilterConfig plain;
  plain.levels = 8;
  plain.min_count = 2;
  FilterConfig searching = plain;
  searching.neighbour_search = true;
  const FilterResult reference = ReferenceFilter(batch, searching);
  ASSERT_EQ(reference.stats.records_searched, 0u);
  EXPECT_TRUE(SameBits(ReferenceFilter(batch, plain).image, reference.image));
  const EmulatedRun emulated = EmulatedFilter(batch, searching, {});
  EXPECT_EQ(emulated.records_searched, 0u);
  EXPECT_TRUE(SameBits(EmulatedFilter(batch, plain, {}).image, emulated.image));
  VulkanFilter vulkan_filter(TestDevice(StagingPolicy::kNever));
  const VulkanRun vulkan = vulkan_filter.Run(batch, searching);
  EXPECT_EQ(vulkan.records_searched, 0u);
  EXPECT_TRUE(SameBits(vulkan_filter.Run(batch, plain).image, vulkan.image));
  const auto forced_is_the_same = [&](const FilterConfig& config, const std::string& name) {
    FilterConfig forced = config;
    forced.forced.Add(Effect::kNeighbourSearch);
    EXPECT_TRUE(SameBits(ReferenceFilter(batch, forced).image, ReferenceFilter(batch, config).image)) << name;
    EXPECT_TRUE(SameBits(EmulatedFilter(batch, forced, {}).image, EmulatedFilter(batch, config, {}).image)) << name;
    EXPECT_TRUE(SameBits(vulkan_filter.Run(batch, forced).image, vulkan_filter.Run(batch, config).image)) << name;
  };
  forced_is_the_same(searching, "forced, none below the threshold");
  // And with records below it, the search changes their pixels.
  searching.levels = plain.levels = 1;
  searching.min_count = 4;
  plain.min_count = 1;
  EXPECT_FALSE(SameBits(ReferenceFilter(batch, plain).image, ReferenceFilter(batch, searching).image));
  EXPECT_GT(vulkan_filter.Run(batch, searching).records_searched, batch.records.size() / 10);
  forced_is_the_same(searching, "forced, two fifths below the threshold");
}

// Each broken variant fails the contract: a lookup that claims the first empty slot (level 2: a tag no record
// carries), a stencil side by truncation (level 3: at negative coordinates it reads other cells than the reference),
// in the emulator and as a shader; and a lookup that stops at a tombstone, over frames of the dolly whose priority
// eviction leaves tombstones in a crowded table (level 3: it misses cells the reference reads).
TEST(NeighbourSearch, EachBrokenSearchFailsTheContract) {
  const std::vector<RecordBatch> cornell = {TracedBatch("cornell", 32, 1)};
  const std::vector<RecordBatch> dolly = TracedFrames(LoadScene(HPSF_SCENES_DIR "/cornell-dolly.json"), 64, 1, 3);
  FilterConfig one_frame;
  one_frame.min_count = 4;
  one_frame.neighbour_search = true;
  FilterConfig pressed = one_frame;
  pressed.frames = 3;
  pressed.eviction = ParseEviction("priority");
  pressed.fingerprint_bits = 31;
  pressed.capacity = 2048;
  const std::string variants = HPSF_SHADER_VARIANT_DIR;
  auto shader = [&](const char* name) {
    VulkanBackendOptions o;
    o.resolve_spv = variants + "/resolve_" + name + ".spv";
    return o;
  };
  struct Variant {
    const char* name;
    std::vector<std::string> backends;
    Defect defect;
    VulkanBackendOptions vulkan;
    const std::vector<RecordBatch>* frames;
    const FilterConfig* config;
    int level;
  };
  const std::vector<Variant> cases = {
      {"emulated search-claims", {"reference", "emulated"}, Defect::kSearchClaims, {}, &cornell, &one_frame, 2},
      {"resolve SEARCH_CLAIMS",
       {"reference", "vulkan"},
       Defect::kNone,
       shader("SEARCH_CLAIMS"),
       &cornell,
       &one_frame,
       2},
      {"emulated stencil-truncated", {"reference", "emulated"}, Defect::kStencilTruncated, {}, &cornell, &one_frame, 3},
      {"resolve STENCIL_TRUNCATED",
       {"reference", "vulkan"},
       Defect::kNone,
       shader("STENCIL_TRUNCATED"),
       &cornell,
       &one_frame,
       3},
      {"emulated search-stops-at-tombstone",
       {"reference", "emulated"},
       Defect::kSearchStopsAtTombstone,
       {},
       &dolly,
       &pressed,
       3},
      {"resolve SEARCH_STOPS_AT_TOMBSTONE",
       {"reference", "vulkan"},
       Defect::kNone,
       shader("SEARCH_STOPS_AT_TOMBSTONE"),
       &dolly,
       &pressed,
       3},
  };
  for (const Variant& v : cases) {
    const CrosscheckReport correct = Crosschecker(v.backends).CheckFrames(*v.frames, *v.config, {});
    EXPECT_TRUE(correct.Passed()) << v.name << ", correct: " << correct.FirstFailure();
    const CrosscheckReport report = Crosschecker(v.backends, v.defect, v.vulkan).CheckFrames(*v.frames, *v.config, {});
    EXPECT_FALSE(Level(report, v.level).passed) << v.name << " escaped level " << v.level;
    std::printf("%s: %s\n", v.name, report.FirstFailure().c_str());
  }
}

// Options: the search needs a threshold above 1, and a threshold above 1 needs levels or the search.
TEST(NeighbourSearch, ASearchWithoutAThresholdNamesItsOption) {
  auto error_of = [](FilterConfig c) -> std::string {
    try {
      c.Validate();
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  FilterConfig c;
  c.neighbour_search = true;
  EXPECT_NE(error_of(c).find("--neighbour-search"), std::string::npos);
  c.min_count = 3;
  EXPECT_EQ(error_of(c), "");
  c.neighbour_search = false;
  EXPECT_NE(error_of(c).find("--min-count"), std::string::npos);
}

}  // namespace
}  // namespace hpsf::testing
