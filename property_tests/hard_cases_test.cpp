// The numerical hard cases (docs/design/tracer.md), through every backend: the reference, the emulator (fast, and
// faithful inside the cross-check) and Vulkan (mapped and staged), in fixed64 and float32 where both mean something.
// Each case asserts that every image pixel is finite, that the cross-check contract holds at every level, and
// that the records keyed, without a vertex, unkeyable and rejected are what the case was built to give; then
// what the case itself is about (a level at its clamp, the F chosen, a firefly kept to its cells, ...). Each
// prints one line of figures for docs/results.md's table ("hard case | ...").
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "core/input_check.h"
#include "core/shared/float_bits.h"
#include "emulated/emulated_filter.h"
#include "property_tests/traced_batch.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_filter.h"
#include "verifier/checker/table_checker.h"
#include "verifier/contract/crosscheck.h"
#include "verifier/contract/image_check.h"

namespace hpsf::testing {
namespace {

constexpr Accumulation kBoth[] = {Accumulation::kFixed64, Accumulation::kFloat32};

// What a case was built to give, per record: keyed, without a vertex, unkeyable, rejected.
struct Counts {
  std::uint64_t keyed = 0, no_vertex = 0, unkeyable = 0, rejected = 0;
  bool operator==(const Counts&) const = default;
  std::string ToString() const {
    return "[ keyed " + std::to_string(keyed) + " no vertex " + std::to_string(no_vertex) + " unkeyable " +
           std::to_string(unkeyable) + " rejected " + std::to_string(rejected) + " ]";
  }
  friend void PrintTo(const Counts& c, std::ostream* os) { *os << c.ToString(); }
};

// The counts a batch must give when `unkeyable` of its accepted vertex records have no cell: the rest follows
// from the records' flags and the input checks alone, not from any backend.
Counts Expected(const RecordBatch& batch, std::uint64_t unkeyable) {
  Counts c;
  for (const Record& r : batch.records) {
    if (CheckRecordInputs(r) != InputVerdict::kAccepted) {
      ++c.rejected;
    } else if (!shared::RecordHasVertex(r)) {
      ++c.no_vertex;
    } else {
      ++c.keyed;
    }
  }
  c.keyed -= unkeyable;
  c.unkeyable = unkeyable;
  return c;
}

Counts CountsOf(const FilterStats& s) {
  return {s.records_with_vertex - s.unkeyable, s.records_without_vertex, s.unkeyable,
          s.rejected_non_finite + s.rejected_negative};
}

// A hashed backend's counts from its own keys; a rejected record's key is never computed, so it is not read.
Counts CountsOf(const RecordBatch& batch, const HashedRun& run) {
  Counts c;
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    if (CheckRecordInputs(batch.records[i]) != InputVerdict::kAccepted) {
      ++c.rejected;
      continue;
    }
    const std::uint32_t status = run.keys[i].status;
    c.keyed += status == shared::kKeyed;
    c.no_vertex += status == shared::kKeyNoVertex;
    c.unkeyable += status == shared::kKeyUnkeyable;
  }
  return c;
}

float MaxAbsPixel(const Image& image) {
  float m = 0.0f;
  for (const glm::vec3& p : image.pixels) m = std::max({m, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return m;
}

void ExpectFinite(const Image& image, const std::string& who) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(image.pixels[i][c]))
          << who << ": pixel " << i << " channel " << c << " is " << image.pixels[i][c];
    }
  }
}

// Every backend's run of one batch and config, for the case's own assertions.
struct CaseRuns {
  FilterResult reference;
  EmulatedRun emulated;           // fast mode
  std::vector<VulkanRun> vulkan;  // one per staging policy, in kStagingPolicies' order
  std::vector<const HashedRun*> Hashed() const {
    std::vector<const HashedRun*> runs = {&emulated};
    for (const VulkanRun& v : vulkan) runs.push_back(&v);
    return runs;
  }
};

std::string BackendName(std::size_t hashed_index) {
  return hashed_index == 0 ? "emulated" : std::string("vulkan ") + ToString(kStagingPolicies[hashed_index - 1]);
}

// Runs every backend and the cross-check, asserts what every case must hold, and prints the case's figures.
CaseRuns RunCase(const std::string& name, const RecordBatch& batch, const FilterConfig& config,
                 const Counts& expected) {
  SCOPED_TRACE(name + ", " + ToString(config.accumulation));
  CaseRuns runs;
  runs.reference = ReferenceFilter(batch, config);
  runs.emulated = EmulatedFilter(batch, config, EmulatorOptions{});
  for (const StagingPolicy staging : kStagingPolicies) runs.vulkan.push_back(TestFilter(staging).Run(batch, config));

  EXPECT_EQ(CountsOf(runs.reference.stats), expected) << "reference";
  ExpectFinite(runs.reference.image, "reference");
  float max_pixel = MaxAbsPixel(runs.reference.image);
  const std::vector<const HashedRun*> hashed = runs.Hashed();
  for (std::size_t b = 0; b < hashed.size(); ++b) {
    const HashedRun& run = *hashed[b];
    const std::string backend = BackendName(b);
    EXPECT_EQ(CountsOf(batch, run), expected) << backend;
    ExpectFinite(run.image, backend);
    max_pixel = std::max(max_pixel, MaxAbsPixel(run.image));
    EXPECT_EQ(run.table.fixed_point_bits, runs.reference.stats.fixed_point_bits) << backend << ": F";
    EXPECT_EQ(run.wraps, 0u) << backend;
    for (std::size_t i = 0; i < batch.records.size(); ++i) {
      if (CheckRecordInputs(batch.records[i]) == InputVerdict::kAccepted) continue;
      EXPECT_EQ(run.placements[i], kNotPlaced) << backend << ": rejected record " << i << " was placed";
      EXPECT_EQ(runs.reference.placement[i], kNoCell) << "reference: rejected record " << i << " has a cell";
    }
    for (const TableViolation& v : CheckTable({run.table, batch.records, run.keys, run.placements})) {
      ADD_FAILURE() << backend << ": " << v.ToString();
    }
    for (const std::string& pixel : CheckImageAgainstTable(batch, run)) ADD_FAILURE() << backend << ": " << pixel;
  }

  // The contract, with the emulator faithful (its float32 order of adds replayed by the reference) and Vulkan
  // over both memory paths.
  EmulatorOptions faithful;
  faithful.mode = simt::Mode::kFaithful;
  faithful.warp_size = 8;
  std::uint64_t probe_failures = 0, aliased_slots = 0;
  for (const StagingPolicy staging : kStagingPolicies) {
    VulkanBackendOptions vulkan;
    vulkan.staging = staging;
    const CrosscheckReport report =
        Crosscheck(batch, config, {"reference", "emulated", "vulkan"}, faithful, Defect::kNone, vulkan);
    for (const LevelVerdict& v : report.levels) {
      EXPECT_TRUE(v.applicable) << "level " << v.level << " was not applied: " << v.note;
      EXPECT_TRUE(v.passed) << "--vk-staging " << ToString(staging) << ", level " << v.level << " (" << v.name
                            << "): " << (v.failures.empty() ? v.note : v.failures.front());
    }
    for (const QualityFigures& q : report.quality) {
      probe_failures = std::max(probe_failures, q.probe_failures);
      aliased_slots = std::max(aliased_slots, q.aliased_slots);
    }
  }
  const Counts& c = expected;
  std::printf("hard case | %s | %s | records %zu | keyed %" PRIu64 " | no vertex %" PRIu64 " | unkeyable %" PRIu64
              " | rejected %" PRIu64 " | cells %" PRIu64 " | F %d | max |pixel| %.4g | probe failures %" PRIu64
              " | aliased slots %" PRIu64 "\n",
              name.c_str(), ToString(config.accumulation).c_str(), batch.records.size(), c.keyed, c.no_vertex,
              c.unkeyable, c.rejected, runs.reference.stats.cells, runs.reference.stats.fixed_point_bits,
              double(max_pixel), probe_failures, aliased_slots);
  return runs;
}

// Small tables: the batches here have at most a few thousand records.
FilterConfig SmallTable(Accumulation accumulation) {
  FilterConfig config;
  config.capacity = 1u << 12;
  config.accumulation = accumulation;
  return config;
}

// Each record's key level, through every backend's keys; `level` for each accepted vertex record.
void ExpectLevels(const RecordBatch& batch, const CaseRuns& runs, int level) {
  const std::vector<const HashedRun*> hashed = runs.Hashed();
  for (std::size_t b = 0; b < hashed.size(); ++b) {
    for (std::size_t i = 0; i < batch.records.size(); ++i) {
      const Record& r = batch.records[i];
      if (!shared::RecordHasVertex(r) || CheckRecordInputs(r) != InputVerdict::kAccepted) continue;
      const KeyResult& k = hashed[b]->keys[i];
      ASSERT_EQ(k.level, level) << BackendName(b) << ": record " << i;
      if (k.status == shared::kKeyed) {
        ASSERT_EQ(k.words.level, std::uint32_t(level + 128)) << BackendName(b);
      }
    }
  }
}

// Bit-identical images, where the filter cannot change a value. A float32 sum of two or more records depends on
// the order the atomics applied it in, so there only the reference (record order) is held to the bits.
void ExpectImage(const CaseRuns& runs, const FilterConfig& config, const Image& expected, const std::string& why) {
  EXPECT_TRUE(SameBits(runs.reference.image, expected)) << "reference: " << why;
  if (config.accumulation == Accumulation::kFloat32 && runs.reference.stats.max_records_per_cell > 1) return;
  const std::vector<const HashedRun*> hashed = runs.Hashed();
  for (std::size_t b = 0; b < hashed.size(); ++b) {
    EXPECT_TRUE(SameBits(hashed[b]->image, expected)) << BackendName(b) << ": " << why;
  }
}

RecordBatch HandMade(std::uint32_t width, std::uint32_t height, std::uint32_t spp,
                     const std::function<Record(std::uint32_t pixel, std::uint32_t sample)>& make) {
  RecordBatch batch;
  batch.width = width;
  batch.height = height;
  batch.samples_per_pixel = spp;
  batch.fov_y_radians = 1.0;
  for (std::uint32_t p = 0; p < width * height; ++p) {
    for (std::uint32_t s = 0; s < spp; ++s) batch.records.push_back(make(p, s));
  }
  return batch;
}

// The index of the n-th record with a vertex (from 0).
std::size_t NthVertexRecord(const RecordBatch& batch, std::size_t n) {
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    if (shared::RecordHasVertex(batch.records[i]) && n-- == 0) return i;
  }
  ADD_FAILURE() << "the batch has too few vertex records";
  return 0;
}

// At 1e5 and 1e7 from the origin (float spacing 2^-7 and 1) every vertex is keyed: cells of 2^l with l from the
// footprint stay far below 2^31 of them.
TEST(HardCases, FarFromTheOrigin) {
  for (const char* scene : {"cornell-far-1e5", "cornell-far-1e7"}) {
    const RecordBatch batch = TracedBatch(scene, 32, 2);
    for (const Accumulation a : kBoth) RunCase(scene, batch, SmallTable(a), Expected(batch, 0));
  }
}

// Exact scaling of a batch by a power of two (positions, previous vertices and d_prefix by 2^-64, so vertices
// lie about 1e-17 from the origin) scales w, the cell size and the jittered position alike: the level drops
// by 64 and every cell index, cell count and pixel stays the same, bit for bit. With level of detail off, the
// cell size scaled alike does the same. cornell-tiny (scaled by 1e-4 by the tracer) is keyed everywhere too.
TEST(HardCases, TinyScenes) {
  const RecordBatch tiny = TracedBatch("cornell-tiny", 32, 2);
  for (const Accumulation a : kBoth) RunCase("cornell-tiny", tiny, SmallTable(a), Expected(tiny, 0));

  const RecordBatch batch = TracedBatch("cornell", 32, 2);
  RecordBatch scaled = batch;
  constexpr int kShift = -64;
  for (Record& r : scaled.records) {
    if (!shared::RecordHasVertex(r)) continue;
    r.position = glm::vec4(std::ldexp(r.position.x, kShift), std::ldexp(r.position.y, kShift),
                           std::ldexp(r.position.z, kShift), std::ldexp(r.position.w, kShift));
    r.previous = glm::vec4(std::ldexp(r.previous.x, kShift), std::ldexp(r.previous.y, kShift),
                           std::ldexp(r.previous.z, kShift), 0.0f);
  }
  for (const bool lod : {true, false}) {
    for (const Accumulation a : kBoth) {
      FilterConfig config = SmallTable(a);
      config.lod = lod;
      config.cell_size = 16.0f;
      const FilterResult original = ReferenceFilter(batch, config);
      config.cell_size = std::ldexp(16.0f, kShift);
      const std::string name = std::string("cornell x 2^-64, lod ") + (lod ? "on" : "off");
      const CaseRuns runs = RunCase(name, scaled, config, Expected(scaled, 0));
      ExpectImage(runs, config, original.image, "the scaled batch must filter to the original's image");
      ASSERT_EQ(runs.reference.cells.size(), original.cells.size());
      for (std::size_t c = 0; c < original.cells.size(); ++c) {
        std::array<std::uint32_t, 6> key = original.cells[c].key;
        key[3] = std::uint32_t(int(key[3]) + kShift);
        ASSERT_EQ(runs.reference.cells[c].key, key) << "cell " << c;
        ASSERT_EQ(runs.reference.cells[c].count, original.cells[c].count) << "cell " << c;
      }
    }
  }
}

// A denormal cell size (or one whose inverse is denormal) never reaches the key path: every backend and the
// cross-check refuse it, naming --cell-size. The smallest normal one, 2^-126, puts every Cornell vertex beyond
// 2^31 cells (q overflows to Inf, caught before conversion): all unkeyable, each record keeps its own
// contribution, so the image is the unfiltered one. A huge one, 1e30, keys everything at the level of its
// exponent, 99, into a handful of cells.
TEST(HardCases, DenormalAndHugeCellSizes) {
  const RecordBatch batch = TracedBatch("cornell", 32, 2);
  for (const float refused : {1e-40f, 1e38f}) {
    FilterConfig config = SmallTable(Accumulation::kFixed64);
    config.lod = false;
    config.cell_size = refused;
    ASSERT_TRUE(std::fpclassify(refused) == FP_SUBNORMAL || std::fpclassify(1.0f / refused) == FP_SUBNORMAL);
    auto expect_refused = [&](const std::function<void()>& run, const char* who) {
      try {
        run();
        ADD_FAILURE() << who << " accepted cell size " << refused;
      } catch (const ConfigError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("--cell-size", 0), 0u) << who << ": " << e.what();
      }
    };
    expect_refused([&] { ReferenceFilter(batch, config); }, "reference");
    expect_refused([&] { EmulatedFilter(batch, config, EmulatorOptions{}); }, "emulated");
    for (const StagingPolicy staging : kStagingPolicies) {
      expect_refused([&] { TestFilter(staging).Run(batch, config); }, "vulkan");
    }
    expect_refused(
        [&] {
          Crosscheck(batch, config, {"reference", "emulated", "vulkan"}, EmulatorOptions{});
        },
        "crosscheck");
    std::printf("hard case | cell size %g | refused | ConfigError --cell-size\n", double(refused));
  }

  const std::uint64_t vertices = Expected(batch, 0).keyed;
  for (const Accumulation a : kBoth) {
    FilterConfig config = SmallTable(a);
    config.lod = false;
    config.cell_size = std::ldexp(1.0f, -126);
    const CaseRuns runs = RunCase("cornell, cell size 2^-126", batch, config, Expected(batch, vertices));
    ExpectLevels(batch, runs, -126);
    ExpectImage(runs, config, UnfilteredImage(batch), "unkeyable records keep their own contribution");
    EXPECT_EQ(runs.reference.stats.cells, 0u);

    config.cell_size = 1e30f;
    const CaseRuns huge = RunCase("cornell, cell size 1e30", batch, config, Expected(batch, 0));
    ExpectLevels(batch, huge, 99);
    // Jittered positions reach 1e30 * sqrt(2) at most: cells -2..1 per axis, times the 8 normal octants.
    EXPECT_LE(huge.reference.stats.cells, 4u * 4u * 4u * 8u);
  }
}

// cornell-zero-red: every albedo's red channel is 0, so every vertex's red throughput is 0. No NaN anywhere,
// and no red light lost: the only red is what paths gathered before the vertex (the light seen directly), which
// the filter must pass through untouched, so every backend's red channel equals the unfiltered image's, bit for
// bit. Green and blue keep their light: the batch's green and blue records are the Cornell box's, and so are
// the reference's filtered green and blue channels in float32, bit for bit.
TEST(HardCases, ZeroAlbedoChannels) {
  const RecordBatch batch = TracedBatch("cornell-zero-red", 32, 2);
  const RecordBatch cornell = TracedBatch("cornell", 32, 2);
  ASSERT_EQ(batch.records.size(), cornell.records.size());
  std::size_t red_arrives = 0;  // vertices where red light arrives, to be multiplied by a zero throughput
  for (const Record& r : batch.records) {
    if (shared::RecordHasVertex(r)) {
      ASSERT_EQ(r.throughput.x, 0.0f);
      red_arrives += r.contribution.x > 0.0f;
    }
  }
  EXPECT_GT(red_arrives, batch.records.size() / 2);
  const Image unfiltered = UnfilteredImage(batch);
  for (const Accumulation a : kBoth) {
    const FilterConfig config = SmallTable(a);
    const CaseRuns runs = RunCase("cornell-zero-red", batch, config, Expected(batch, 0));
    const FilterResult box = ReferenceFilter(cornell, config);
    std::vector<const Image*> images = {&runs.reference.image};
    for (const HashedRun* run : runs.Hashed()) images.push_back(&run->image);
    for (std::size_t b = 0; b < images.size(); ++b) {
      for (std::size_t p = 0; p < unfiltered.pixels.size(); ++p) {
        ASSERT_EQ(images[b]->pixels[p].x, unfiltered.pixels[p].x) << "image " << b << " pixel " << p;
      }
    }
    // fixed64 rounds to the batch's F, which the Cornell box's larger red totals lower by one; float32 adds the
    // same green and blue values in the same order.
    if (a != Accumulation::kFloat32) continue;
    for (std::size_t p = 0; p < unfiltered.pixels.size(); ++p) {
      ASSERT_EQ(runs.reference.image.pixels[p].y, box.image.pixels[p].y) << "pixel " << p;
      ASSERT_EQ(runs.reference.image.pixels[p].z, box.image.pixels[p].z) << "pixel " << p;
    }
  }
}

// Four fireflies of radiance 1e6 among 2048 ordinary Cornell records: fixed64 picks a smaller F for them, and a
// firefly's light stays in its own cells: in float32 every pixel none of whose records shares a cell with a
// firefly is bit-identical to the batch without them.
TEST(HardCases, FirefliesOfRadiance1e6) {
  const RecordBatch plain = TracedBatch("cornell", 32, 2);
  RecordBatch batch = plain;
  std::vector<std::size_t> fireflies;
  for (std::size_t n : {100u, 600u, 1100u, 1600u}) {
    fireflies.push_back(NthVertexRecord(batch, n));
    batch.records[fireflies.back()].contribution = glm::vec4(1e6f, 1e6f, 1e6f, 0.0f);
  }
  for (const Accumulation a : kBoth) {
    const FilterConfig config = SmallTable(a);
    const CaseRuns runs = RunCase("cornell + 4 fireflies of 1e6", batch, config, Expected(batch, 0));
    const FilterResult without = ReferenceFilter(plain, config);
    EXPECT_LT(runs.reference.stats.fixed_point_bits, without.stats.fixed_point_bits);
    if (a != Accumulation::kFloat32) continue;
    std::vector<bool> hot_cell(runs.reference.cells.size(), false);
    for (std::size_t i : fireflies) hot_cell[runs.reference.placement[i]] = true;
    std::uint32_t untouched = 0;
    for (std::uint32_t p = 0; p < batch.width * batch.height; ++p) {
      bool hot = false;
      for (std::uint32_t s = 0; s < batch.samples_per_pixel; ++s) {
        const std::uint32_t cell = runs.reference.placement[p * batch.samples_per_pixel + s];
        hot = hot || (cell != kNoCell && hot_cell[cell]);
      }
      if (hot) continue;
      ++untouched;
      ASSERT_EQ(runs.reference.image.pixels[p], without.image.pixels[p]) << "pixel " << p;
    }
    EXPECT_GT(untouched, batch.width * batch.height / 2);
  }
}

// One mixed batch of inputs a shader must never see (rejected_inputs_test covers every field): NaN, +Inf and
// -Inf, and a negative throughput, among ordinary records; a -0.0 contribution is not negative and is kept. The
// expected counts come from the construction, not from the input checks under test.
TEST(HardCases, NonFiniteAndNegativeRecordsInOneBatch) {
  const RecordBatch clean = TracedBatch("cornell", 16, 2);
  RecordBatch batch = clean;
  const std::size_t nan = NthVertexRecord(batch, 10), inf = NthVertexRecord(batch, 50),
                    negative = NthVertexRecord(batch, 90), negative_zero = NthVertexRecord(batch, 130);
  const std::size_t last = batch.records.size() - 1;  // becomes a sample without a vertex whose radiance is -Inf
  batch.records[nan].contribution.y = std::numeric_limits<float>::quiet_NaN();
  batch.records[inf].position.x = INFINITY;
  batch.records[negative].throughput.z = -0.5f;
  batch.records[negative_zero].contribution.x = -0.0f;
  batch.records[last] =
      MakeRecordWithoutVertex(batch.records[last].path.x, batch.records[last].path.y, glm::vec3(-INFINITY, 0.0f, 0.0f));
  Counts expected = Expected(clean, 0);
  ASSERT_EQ(expected.rejected, 0u);
  expected.keyed -= 3;
  (shared::RecordHasVertex(clean.records[last]) ? expected.keyed : expected.no_vertex) -= 1;
  expected.rejected = 4;
  for (const Accumulation a : kBoth) {
    const CaseRuns runs = RunCase("cornell + NaN, Inf, -Inf, negative", batch, SmallTable(a), expected);
    EXPECT_EQ(runs.reference.stats.rejected_non_finite, 3u);
    EXPECT_EQ(runs.reference.stats.rejected_negative, 1u);
    EXPECT_NE(runs.reference.placement[negative_zero], kNoCell);
    for (const std::size_t i : {nan, inf, negative, last}) {
      EXPECT_EQ(runs.reference.placement[i], kNoCell) << "reference: record " << i;
      for (const HashedRun* run : runs.Hashed()) EXPECT_EQ(run->placements[i], kNotPlaced) << "record " << i;
    }
  }
}

// The camera on a surface: x == x_prev and d_prefix 0, so the path length and w are 0 and the level is
// level_min. At the default -126 a cell is 2^-126 wide and every vertex but the one at the origin is beyond
// 2^31 cells: unkeyable, unfiltered. With level_min -10 every vertex is keyed at level -10 in a cell of its
// own. A lone record in a cell averages to itself, so either way the image is the unfiltered one.
TEST(HardCases, CameraOnASurface) {
  const RecordBatch batch = HandMade(8, 8, 1, [](std::uint32_t pixel, std::uint32_t) {
    VertexSample v;
    v.pixel = pixel;
    v.position = pixel == 0 ? glm::vec3(0.0f) : glm::vec3(float(pixel % 8) + 0.5f, float(pixel / 8) + 0.5f, 5.0f);
    v.previous = v.position;
    v.d_prefix = 0.0f;
    v.normal = glm::vec3(0.0f, 0.0f, -1.0f);
    v.contribution = glm::vec3(0.5f, 0.25f, 0.125f);
    v.throughput = glm::vec3(0.75f, 0.5f, 1.0f);
    v.radiance_before = glm::vec3(0.0625f);
    return MakeVertexRecord(v);
  });
  const Image unfiltered = UnfilteredImage(batch);
  for (const Accumulation a : kBoth) {
    FilterConfig config = SmallTable(a);
    const CaseRuns at_minimum = RunCase("camera on a surface, level_min -126", batch, config, Expected(batch, 63));
    ExpectLevels(batch, at_minimum, -126);
    EXPECT_NE(at_minimum.reference.placement[0], kNoCell);
    ExpectImage(at_minimum, config, unfiltered, "lone and unkeyable records keep their own contribution");

    config.level_min = -10;
    const CaseRuns clamped = RunCase("camera on a surface, level_min -10", batch, config, Expected(batch, 0));
    ExpectLevels(batch, clamped, -10);
    EXPECT_EQ(clamped.reference.stats.cells, 64u);
    ExpectImage(clamped, config, unfiltered, "a lone record in its cell averages to itself");
  }
}

// Four records of contribution 2^58 among ordinary Cornell records: their total alone is 2^60, so F = 3 would
// reach 2^63 and the largest F that fits is 2 whatever the ordinary records add. Every backend uses it and no
// sum wraps. What it costs: a cell of ordinary records averages to within half a unit of 2^-F of its exact
// average (a float's few exponents sum exactly in double).
TEST(HardCases, LargeTotalsForceASmallF) {
  RecordBatch batch = TracedBatch("cornell", 32, 2);
  std::vector<std::size_t> large;
  for (std::size_t n : {0u, 500u, 1000u, 1500u}) {
    large.push_back(NthVertexRecord(batch, n));
    batch.records[large.back()].contribution = glm::vec4(0x1p58f, 0x1p58f, 0x1p58f, 0.0f);
  }
  const CaseRuns runs =
      RunCase("cornell + 4 records of 2^58", batch, SmallTable(Accumulation::kFixed64), Expected(batch, 0));
  const int f = runs.reference.stats.fixed_point_bits;
  EXPECT_EQ(f, 2);
  EXPECT_LT(f, 8);
  constexpr unsigned __int128 kLimit = static_cast<unsigned __int128>(1) << 63;
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(FixedPointCeilingSum(batch.records, c, f), kLimit) << "channel " << c;
    EXPECT_GE(FixedPointCeilingSum(batch.records, c, f + 1), kLimit) << "channel " << c;
  }
  std::vector<glm::dvec3> exact(runs.reference.cells.size(), glm::dvec3(0.0));
  std::vector<bool> holds_large(runs.reference.cells.size(), false);
  for (std::size_t i = 0; i < batch.records.size(); ++i) {
    const std::uint32_t cell = runs.reference.placement[i];
    if (cell != kNoCell) exact[cell] += glm::dvec3(batch.records[i].contribution);
  }
  for (std::size_t i : large) holds_large[runs.reference.placement[i]] = true;
  double worst = 0.0;
  for (std::size_t k = 0; k < exact.size(); ++k) {
    if (holds_large[k]) continue;
    const TableCell& cell = runs.reference.cells[k];
    for (int c = 0; c < 3; ++c) {
      const double n = double(cell.count);
      worst = std::max(worst, std::abs(FromFixedPoint(cell.fixed_sum[c], f) / n - exact[k][c] / n));
    }
  }
  EXPECT_LE(worst, std::ldexp(0.5, -f));
  std::printf(
      "hard case | cornell + 4 records of 2^58 | fixed64 | F %d | worst error of an ordinary cell's average"
      " %.4g\n",
      f, worst);
}

// One float32 cell of 128 records whose contributions alternate 1e30 and 1e-30 (red), the other way round
// (green), and 1 (blue): every backend's slot sum stays within gamma(n-1) sum|c| of the exact sum and every
// pixel is finite. fixed64 runs the same batch: F drops to -43 and the 1e-30s round to 0, inside the
// same half unit.
TEST(HardCases, Float32CellMixing1eMinus30And1e30) {
  const RecordBatch batch = HandMade(4, 4, 8, [](std::uint32_t pixel, std::uint32_t sample) {
    VertexSample v;
    v.pixel = pixel;
    v.sample = sample;
    v.position = glm::vec3(0.5f, 0.5f, 0.5f);
    v.previous = glm::vec3(0.5f, 0.5f, -1.5f);
    const bool odd = (pixel + sample) % 2 == 1;
    v.contribution = glm::vec3(odd ? 1e30f : 1e-30f, odd ? 1e-30f : 1e30f, 1.0f);
    v.throughput = glm::vec3(0.5f);
    return MakeVertexRecord(v);
  });
  for (const Accumulation a : kBoth) {
    FilterConfig config = SmallTable(a);
    config.lod = false;
    config.cell_size = 1.0f;
    config.jitter_scale = 0.0f;
    const CaseRuns runs = RunCase("one cell of 1e30 and 1e-30", batch, config, Expected(batch, 0));
    ASSERT_EQ(runs.reference.cells.size(), 1u);
    // 64 x 1e30 is 2^105.6: F = -42 would give 2^63.6.
    EXPECT_EQ(runs.reference.stats.fixed_point_bits, -43);
    glm::dvec3 exact(0.0), magnitude(0.0);
    for (const Record& r : batch.records) {
      exact += glm::dvec3(r.contribution);
      magnitude += glm::abs(glm::dvec3(r.contribution));
    }
    const double k = double(batch.records.size() - 1), u = 0x1p-23;
    for (const HashedRun* run : runs.Hashed()) {
      const std::uint32_t slot = run->placements[0];
      ASSERT_LT(slot, run->table.capacity);
      EXPECT_EQ(run->table.counts[slot], batch.records.size());
      for (int c = 0; c < 3; ++c) {
        const double sum = a == Accumulation::kFloat32
                               ? double(run->table.float_sums[slot][c])
                               : FromFixedPoint(run->table.fixed_sums[slot][c], run->table.fixed_point_bits);
        const double bound = a == Accumulation::kFloat32
                                 ? k * u / (1.0 - k * u) * magnitude[c]
                                 : double(batch.records.size()) * std::ldexp(0.5, -run->table.fixed_point_bits);
        EXPECT_LE(std::abs(sum - exact[c]), bound) << "channel " << c;
      }
    }
  }
}

// float32 cell sums that could overflow: four records of 2e38 in one cell total 8e38, above the float range
// (3.4e38). Every backend refuses the batch in float32 with a ConfigError naming --accum (the command line's
// exit 3) instead of summing to Inf; fixed64 takes it at F = -67. Four records of 2^125 (total 2^127) are
// refused too, since at F = -64 their ceilings sum to 2^63 exactly; four of 2^124 (total 2^126) give F = -64,
// the lowest float32 takes, and filter to finite pixels.
TEST(HardCases, Float32RefusesTotalsThatCouldOverflow) {
  auto four_records_of = [](float contribution) {
    return HandMade(2, 2, 1, [contribution](std::uint32_t pixel, std::uint32_t sample) {
      VertexSample v;
      v.pixel = pixel;
      v.sample = sample;
      v.position = glm::vec3(0.5f, 0.5f, 0.5f);
      v.previous = glm::vec3(0.5f, 0.5f, -1.5f);
      v.contribution = glm::vec3(contribution, 1.0f, 1.0f);
      v.throughput = glm::vec3(0.5f);
      return MakeVertexRecord(v);
    });
  };
  auto one_cell = [](Accumulation a) {
    FilterConfig config = SmallTable(a);
    config.lod = false;
    config.cell_size = 1.0f;
    config.jitter_scale = 0.0f;
    return config;
  };
  const RecordBatch over = four_records_of(2e38f);
  const FilterConfig float32 = one_cell(Accumulation::kFloat32);
  auto expect_refused = [](const std::function<void()>& run, const std::string& backend) {
    try {
      run();
      ADD_FAILURE() << backend << " summed the batch in float32";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("--accum"), std::string::npos) << backend << ": " << e.what();
    }
  };
  expect_refused([&] { ReferenceFilter(over, float32); }, "reference");
  expect_refused([&] { EmulatedFilter(over, float32, EmulatorOptions{}); }, "emulated");
  for (const StagingPolicy staging : kStagingPolicies) {
    expect_refused([&] { TestFilter(staging).Run(over, float32); }, std::string("vulkan ") + ToString(staging));
  }
  const CaseRuns fixed = RunCase("one cell of 4 x 2e38", over, one_cell(Accumulation::kFixed64), Expected(over, 0));
  EXPECT_EQ(fixed.reference.stats.fixed_point_bits, -67);

  expect_refused([&] { ReferenceFilter(four_records_of(0x1p125f), float32); }, "reference, 4 x 2^125");
  const RecordBatch under = four_records_of(0x1p124f);
  const CaseRuns runs = RunCase("one cell of 4 x 2^124", under, float32, Expected(under, 0));
  EXPECT_EQ(runs.reference.stats.fixed_point_bits, kFloat32FixedPointBitsMin);
}

// The level clamps at both ends of [-126, 126], the widest range the config accepts (-127 and 127 are
// refused): 2^l and 2^-l are normal there. +126: a filter width of 1e37 pixels puts w at 2^127 or Inf for every
// Cornell vertex; the jitter of 2^126 moves positions to about 1e38, still finite and keyed. -126: vertices
// within 2^-97 of the origin and a filter width of 1e-9 pixels make w denormal, flushed to 0, so the level is
// level_min; with no jitter, the cell of x is floor(x 2^126) exactly.
TEST(HardCases, LevelClampsAtMinus126And126) {
  for (const int outside : {-127, 127}) {
    FilterConfig config;
    (outside < 0 ? config.level_min : config.level_max) = outside;
    EXPECT_THROW(config.Validate(), ConfigError) << outside;
  }
  for (const int level : {-126, 126}) {
    EXPECT_TRUE(std::isnormal(shared::PowerOfTwo(level)) && std::isnormal(shared::PowerOfTwo(-level))) << level;
  }

  const RecordBatch cornell = TracedBatch("cornell", 32, 1);
  const RecordBatch tiny = HandMade(8, 8, 1, [](std::uint32_t pixel, std::uint32_t) {
    VertexSample v;
    v.pixel = pixel;
    v.position = glm::vec3(float(pixel % 8) + 0.5f, float(pixel / 8) + 0.5f, 3.0f) * 0x1p-100f;
    v.previous = glm::vec3(v.position.x, v.position.y, -5.0f * 0x1p-100f);
    v.normal = glm::vec3(0.0f, 0.0f, -1.0f);
    v.contribution = glm::vec3(0.5f);
    v.throughput = glm::vec3(1.0f);
    return MakeVertexRecord(v);
  });
  for (const Accumulation a : kBoth) {
    FilterConfig config = SmallTable(a);
    config.level_min = -126;
    config.level_max = 126;
    config.filter_width_px = 1e37f;
    const CaseRuns top = RunCase("cornell, level clamped at 126", cornell, config, Expected(cornell, 0));
    ExpectLevels(cornell, top, 126);

    config.filter_width_px = 1e-9f;
    config.jitter_scale = 0.0f;
    const CaseRuns bottom = RunCase("near the origin, level clamped at -126", tiny, config, Expected(tiny, 0));
    ExpectLevels(tiny, bottom, -126);
    for (const HashedRun* run : bottom.Hashed()) {
      for (std::uint32_t p = 0; p < 64; ++p) {
        const KeyResult& k = run->keys[p];
        ASSERT_EQ(int(k.words.cell_x), int(p % 8) * (1 << 26) + (1 << 25)) << p;
        ASSERT_EQ(int(k.words.cell_y), int(p / 8) * (1 << 26) + (1 << 25)) << p;
        ASSERT_EQ(int(k.words.cell_z), 3 * (1 << 26)) << p;
      }
    }
  }
}

}  // namespace
}  // namespace hpsf::testing
