// Several filtered bounces (Meijer §4.3, nHPSF; core/transport.h): a record whose path scattered to a further vertex
// adds the previous frame's average at that vertex's cell, so a table of K frames holds up to K + 1 bounces. Held
// to the analytic furnace: every record emits e beyond its filter vertex and carries back a of its scattered
// vertex's cell, so each cell's average follows a series whose limit is e / (1 - a). Label `bounces`.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "emulated/emulated_backend.h"
#include "property_tests/transport_furnace.h"
#include "property_tests/vulkan_test_devices.h"
#include "reference/reference_backend.h"
#include "reference/reference_filter.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

// Every cell's average after each frame, computed apart from hpsf: frame k's records each carry e + a c(k-1) (c(-1)
// = 0), and the cell blends them with its history as --temporal says (docs/design/algorithm.md, "Temporal
// blending"): integrate keeps every frame's sums; ema:ALPHA weighs the history by min(ALPHA, N_old / (N_old + N_new))
// and keeps the count ceil(N_new / (1 - alpha)), capped at N_old + N_new.
std::vector<glm::dvec3> ExpectedAverages(const Temporal& temporal, std::uint32_t frames) {
  std::vector<glm::dvec3> averages;
  glm::dvec3 average(0.0);
  double count = 0.0;
  const double added = kPerCell;
  for (std::uint32_t k = 0; k < frames; ++k) {
    const glm::dvec3 frame_value = glm::dvec3(kEmission) + glm::dvec3(kAlbedo) * average;
    double alpha = count / (count + added);
    if (temporal.mode == TemporalMode::kEma) alpha = std::min(temporal.alpha, alpha);
    average = alpha * average + (1.0 - alpha) * frame_value;
    count = k == 0 ? added : std::min(std::ceil(added / (1.0 - alpha)), count + added);
    averages.push_back(average);
  }
  return averages;
}

// The series a table of the newest frame alone holds: e (1 + a + ... + a^k).
glm::dvec3 FurnaceSeries(std::uint32_t k) {
  glm::dvec3 sum(0.0), power(1.0);
  for (std::uint32_t j = 0; j <= k; ++j, power *= glm::dvec3(kAlbedo)) sum += glm::dvec3(kEmission) * power;
  return sum;
}

// A cell's average from a table cell's sums.
glm::dvec3 CellAverage(const TableCell& cell, Accumulation accumulation, int fixed_point_bits) {
  StencilTotal total;
  total.Add(cell.fixed_sum, cell.float_sum, cell.count);
  return total.Average(accumulation, fixed_point_bits);
}

// Within relative tolerance `tolerance`: fixed64 rounds each frame's transported contribution to float once (2^-24)
// and sums exactly, and 2^-20 holds 24 frames of that with room. A float32 sum of n adds is within n 2^-24 of the
// exact one (recursive summation of positive terms), the blend's difference and the transport's rounding add two
// more, and the transport carries a of the previous frame's error along: (n + 2) 2^-24 / (1 - a) bounds the sum of
// that series, a = 3/4 the largest albedo. Either is far below the a^k of one bounce more or less.
void ExpectNear(const glm::dvec3& got, const glm::dvec3& want, double tolerance, const std::string& where) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], want[c] * tolerance) << where << ", channel " << c;
}

// In a table that forgets its history (ema:2^-30), each cell holds the newest frame alone, e (1 + a + ... + a^k) after
// frame k: one bounce more per frame, towards e / (1 - a). Integrating instead keeps the early frames' fewer bounces
// in its sums: the cell follows the integrating series, still converging to e / (1 - a) but as a mean of all frames.
// The reference and the emulator, fast and faithful, in fixed64 and float32.
TEST(Transport, TheFurnaceGainsOneBouncePerFrame) {
  constexpr std::uint32_t kFrames = 24;
  for (const std::string temporal : {"ema:0.000000000931322574615478515625", "integrate"}) {
    for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
      const FilterConfig config = FurnaceConfig(accumulation, temporal, kFrames);
      const std::vector<glm::dvec3> expected = ExpectedAverages(config.temporal, kFrames);
      EmulatorOptions faithful;
      faithful.mode = simt::Mode::kFaithful;
      faithful.warp_size = 8;
      faithful.schedule = "random:3";
      ReferenceBackend reference;
      EmulatedBackend fast{EmulatorOptions{}};
      EmulatedBackend slow{faithful};
      VulkanBackend mapped{TestDevice(StagingPolicy::kNever)};
      VulkanBackend staged{TestDevice(StagingPolicy::kAlways)};
      for (std::uint32_t k = 0; k < kFrames; ++k) {
        const RecordBatch batch = FurnaceBatch(k);
        FilterConfig frame_config = config;
        frame_config.frame = k;
        const std::string where = temporal + ", " + ToString(accumulation) + ", frame " + std::to_string(k);
        reference.FilterFrame(batch, frame_config);
        const FilterResult& exact = *reference.LastExactResult();
        ASSERT_EQ(exact.cells.size(), kCells) << where;
        for (const TableCell& cell : exact.cells) {
          const double tolerance = accumulation == Accumulation::kFixed64
                                       ? std::ldexp(1.0, -20)
                                       : double(cell.count + 2) * std::ldexp(1.0, -24) * 4.0;
          ExpectNear(CellAverage(cell, accumulation, exact.stats.fixed_point_bits), expected[k], tolerance, where);
        }
        if (temporal != "integrate") {
          ExpectNear(expected[k], FurnaceSeries(k), std::ldexp(1.0, -20), where + ", the series");
        }
        EXPECT_EQ(exact.stats.transport.found, k == 0 ? 0u : kCells * kPerCell) << where;
        for (Backend* backend : std::initializer_list<Backend*>{&fast, &slow, &mapped, &staged}) {
          const Image& image = backend->FilterFrame(batch, frame_config);
          const HashedRun& run = *backend->LastHashedRun();
          EXPECT_EQ(run.transport.found, exact.stats.transport.found) << where << ", " << backend->Name();
          if (accumulation != Accumulation::kFixed64) continue;
          // fixed64: the same bits as the reference, slot by cell and pixel by pixel.
          for (std::size_t i = 0; i < batch.records.size(); ++i) {
            const std::uint32_t slot = run.placements[i];
            ASSERT_LT(slot, config.capacity) << where;
            const TableCell& cell = exact.cells[exact.placement[i]];
            EXPECT_EQ(run.table.fixed_sums[slot], cell.fixed_sum) << where << ", record " << i;
            EXPECT_EQ(run.table.counts[slot], cell.count) << where << ", record " << i;
          }
          EXPECT_EQ(image.pixels, exact.image.pixels) << where << ", " << backend->Name();
        }
      }
      const glm::dvec3 limit = glm::dvec3(kEmission) / (glm::dvec3(1.0) - glm::dvec3(kAlbedo));
      std::printf("%s, %s: after %u frames a cell holds %.6f %.6f %.6f of the limit %.6f %.6f %.6f\n", temporal.c_str(),
                  ToString(accumulation).c_str(), kFrames, expected.back().x, expected.back().y, expected.back().z,
                  limit.x, limit.y, limit.z);
    }
  }
}

// Where the light varies from cell to cell, each cell integrates e_c + a times the average of the cells its records
// scatter into, frame by frame (computed apart from hpsf, cell by cell): a record that read another cell than its
// scattered vertex's, or its own, would miss it.
TEST(Transport, EachRecordReadsItsScatteredVertexsCell) {
  constexpr std::uint32_t kFrames = 8;
  const FilterConfig config = FurnaceConfig(Accumulation::kFixed64, "integrate", kFrames);
  std::vector<glm::dvec3> sums(kCells, glm::dvec3(0.0)), averages(kCells, glm::dvec3(0.0));
  ReferenceBackend reference;
  EmulatedBackend emulated{EmulatorOptions{}};
  VulkanBackend vulkan{TestDevice(StagingPolicy::kNever)};
  for (std::uint32_t k = 0; k < kFrames; ++k) {
    const std::vector<glm::dvec3> before = averages;
    for (std::uint32_t c = 0; c < kCells; ++c) {
      for (std::uint32_t j = 0; j < kPerCell; ++j) {
        sums[c] += glm::dvec3(EmissionOf(c, true)) + glm::dvec3(kAlbedo) * before[ScatteredCell(c, j)];
      }
      averages[c] = sums[c] / double(kPerCell * (k + 1));
    }
    const RecordBatch batch = FurnaceBatch(k, true);
    FilterConfig frame_config = config;
    frame_config.frame = k;
    reference.FilterFrame(batch, frame_config);
    emulated.FilterFrame(batch, frame_config);
    const FilterResult& exact = *reference.LastExactResult();
    for (std::uint32_t c = 0; c < kCells; ++c) {
      const std::string where = "frame " + std::to_string(k) + ", cell " + std::to_string(c);
      const TableCell& cell = exact.cells[exact.placement[c * kPerCell]];
      ExpectNear(CellAverage(cell, Accumulation::kFixed64, exact.stats.fixed_point_bits), averages[c],
                 std::ldexp(1.0, -20), where);
    }
    EXPECT_EQ(emulated.run().image.pixels, exact.image.pixels) << "frame " << k;
    EXPECT_EQ(vulkan.FilterFrame(batch, frame_config).pixels, exact.image.pixels) << "frame " << k;
    EXPECT_EQ(vulkan.run().transport.found, exact.stats.transport.found) << "frame " << k;
  }
}

// The traced furnace (albedo a = 1/2, emission 1: radiance L = 2 everywhere), each path filtering `filtered` vertices
// and ending at the vertex the last one scatters to: each record holds one bounce of light, and the transport adds one
// per frame, towards 2, in a table that forgets its history: the image mean after frame k is 2 - 2^-(k+1) but for
// what the transport's misses lose. A miss (a scattered vertex whose cell the table before the frame never held)
// loses at most a L; the cells' deficit D then obeys D <= a (m L + D) for a miss fraction m, so D <= a m L / (1 - a)
// = 2 m, and a pixel's, a D, is below it. The image mean lies within that and 0.005 (the noise of a frame's mean at
// 32 x 32 x 4: frame 0's is 0.0014 from 1.5) of the series. With one filtered vertex most lookups miss: a scattered
// vertex's cell is at its own, coarser level, or on a surface no primary vertex reaches. Measured (docs/design/
// algorithm.md): the mean after 12 frames 1.564 with 1 filtered vertex (78% missed), 1.943 with 2 (5.4%), 1.984 with
// 3 (1.5%). The emulator gives the reference's pixels, bit for bit, with the deeper records in its table.
TEST(Transport, TheTracedFurnaceGainsOneBouncePerFrame) {
  const Scene furnace = LoadScene(HPSF_SCENES_DIR "/furnace.json");
  for (const std::uint32_t filtered : {1u, 2u, 3u}) {
    FilterConfig config;
    config.temporal = ParseTemporal("ema:0.000000000931322574615478515625");
    config.transport = true;
    config.frames = 12;
    config.capacity = 1u << 16;
    ReferenceBackend reference;
    EmulatedBackend emulated{EmulatorOptions{}};
    VulkanBackend vulkan{TestDevice(StagingPolicy::kNever)};
    double worst_miss = 0.0;
    for (std::uint32_t k = 0; k < config.frames; ++k) {
      TraceOptions trace;
      trace.width = trace.height = 32;
      trace.samples_per_pixel = 4;
      trace.frame = config.frame = k;
      trace.scattered = true;
      trace.filtered_vertices = filtered;
      const RecordBatch batch = TraceRecords(furnace, trace).batch;
      const Image& image = reference.FilterFrame(batch, config);
      // The emulator, whose table holds nothing failed or aliased here, gives the same bits (fixed64).
      EXPECT_EQ(emulated.FilterFrame(batch, config).pixels, image.pixels) << filtered << " filtered, frame " << k;
      EXPECT_EQ(emulated.run().probe_failures, 0u);
      EXPECT_EQ(vulkan.FilterFrame(batch, config).pixels, image.pixels) << filtered << " filtered, frame " << k;
      double mean = 0.0;
      for (const glm::vec3& pixel : image.pixels) mean += double(pixel.x);
      mean /= double(image.pixels.size());
      const TransportStats& t = reference.LastExactResult()->stats.transport;
      if (k > 0) worst_miss = std::max(worst_miss, double(t.missed) / double(t.scattered));
      const double series = 2.0 - std::ldexp(1.0, -int(k) - 1);
      std::printf("%u filtered, frame %2u: image mean %.5f, series %.5f; %llu scattered, %llu found, %llu missed\n",
                  filtered, k, mean, series, (unsigned long long)t.scattered, (unsigned long long)t.found,
                  (unsigned long long)t.missed);
      EXPECT_LE(mean, series + 0.005) << filtered << " filtered, frame " << k;
      EXPECT_GE(mean, series - 2.0 * worst_miss - 0.005) << filtered << " filtered, frame " << k;
    }
    if (filtered == 1) {
      EXPECT_GT(worst_miss, 0.5);
    } else if (filtered == 3) {
      EXPECT_LT(worst_miss, 0.03);
    }
  }
}

// The first frame has no table before it: nothing is transported, and the frame equals one filtered without the
// transport, bit for bit. A batch with scattered vertices but not one per record is bad input.
TEST(Transport, TheFirstFrameTransportsNothing) {
  const RecordBatch batch = FurnaceBatch(0);
  FilterConfig with = FurnaceConfig(Accumulation::kFixed64, "integrate", 1);
  FilterConfig without = with;
  without.transport = false;
  const FilterResult a = ReferenceFilter(batch, with);
  const FilterResult b = ReferenceFilter(batch, without);
  EXPECT_EQ(a.image.pixels, b.image.pixels);
  EXPECT_EQ(a.stats.transport.found, 0u);
  RecordBatch uneven = batch;
  uneven.scattered.pop_back();
  EXPECT_THROW(ReferenceFilter(uneven, with), InputError);
}

// Forced on the first frame (--force-effect transport), the pass looks every scattered vertex up in the empty table
// before it, finds nothing and changes no bit: the reference's and the emulator's images and tables are those of the
// frame it skips, in fixed64 and float32; skipped, the emulator's transport timer reads exactly 0.
TEST(Transport, ForcedOnTheFirstFrameItFindsNothingAndChangesNoBit) {
  const RecordBatch batch = TracedFurnaceFrames(2, 1, 16, 2)[0];
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    FilterConfig planned;
    planned.transport = true;
    planned.capacity = 4096;
    planned.accumulation = accumulation;
    FilterConfig forced = planned;
    forced.forced.Add(Effect::kTransport);
    ReferenceBackend reference_planned, reference_forced;
    const Image& a = reference_planned.FilterFrame(batch, planned);
    const Image& b = reference_forced.FilterFrame(batch, forced);
    EXPECT_EQ(a.pixels, b.pixels) << ToString(accumulation);
    EXPECT_EQ(reference_planned.LastExactResult()->stats.transport.scattered, 0u);
    EXPECT_GT(reference_forced.LastExactResult()->stats.transport.scattered, 0u);
    EXPECT_EQ(reference_forced.LastExactResult()->stats.transport.found, 0u);
    EmulatorOptions one_worker;
    one_worker.threads = 1;
    EmulatedBackend emulated_planned(one_worker), emulated_forced(one_worker);
    emulated_planned.FilterFrame(batch, planned);
    emulated_forced.FilterFrame(batch, forced);
    const EmulatedRun& p = emulated_planned.run();
    const EmulatedRun& f = emulated_forced.run();
    EXPECT_EQ(p.image.pixels, f.image.pixels) << ToString(accumulation);
    EXPECT_EQ(p.table.tags, f.table.tags);
    EXPECT_EQ(p.table.counts, f.table.counts);
    EXPECT_EQ(p.table.fixed_sums, f.table.fixed_sums);
    EXPECT_EQ(p.table.float_sums, f.table.float_sums);
    EXPECT_EQ(p.timings.transport_ms, 0.0);
    EXPECT_TRUE(p.transport_read.empty());
    EXPECT_EQ(f.transport.found, 0u);
    EXPECT_GT(f.transport.missed, 0u);
    // Vulkan's pass, forced, probes no slot of the device table (which may hold an earlier sequence's cells).
    VulkanBackend vulkan_planned{TestDevice(StagingPolicy::kNever)}, vulkan_forced{TestDevice(StagingPolicy::kAlways)};
    EXPECT_EQ(vulkan_planned.FilterFrame(batch, planned).pixels, a.pixels) << ToString(accumulation);
    EXPECT_EQ(vulkan_forced.FilterFrame(batch, forced).pixels, a.pixels) << ToString(accumulation);
    EXPECT_EQ(vulkan_planned.run().table.counts, vulkan_forced.run().table.counts);
    EXPECT_TRUE(vulkan_planned.run().transport_read.empty());
    EXPECT_EQ(vulkan_forced.run().transport.found, 0u);
    EXPECT_EQ(vulkan_forced.run().transport.missed, f.transport.missed);
    EXPECT_EQ(vulkan_forced.run().transport.unkeyable, f.transport.unkeyable);
  }
}

// A scattered vertex whose cell the table before the frame never held transports nothing (a miss, counted), and one
// that is rejected as input (a negative weight) is not looked up.
TEST(Transport, AMissTransportsNothing) {
  const FilterConfig config = FurnaceConfig(Accumulation::kFixed64, "integrate", 2);
  ReferenceBackend reference;
  EmulatedBackend emulated{EmulatorOptions{}};
  VulkanBackend vulkan{TestDevice(StagingPolicy::kAlways)};
  RecordBatch next = FurnaceBatch(1);
  next.scattered[0].position.x += 100.0f;  // a cell no frame reached
  next.scattered[1].throughput.y = -1.0f;
  FilterConfig frame_config = config;
  frame_config.frame = 1;
  for (Backend* backend : std::initializer_list<Backend*>{&reference, &emulated, &vulkan}) {
    backend->FilterFrame(FurnaceBatch(0), config);
    backend->FilterFrame(next, frame_config);
    const TransportStats& stats =
        backend == &reference ? reference.LastExactResult()->stats.transport : backend->LastHashedRun()->transport;
    EXPECT_EQ(stats.scattered, kCells * kPerCell - 1) << backend->Name();
    EXPECT_EQ(stats.missed, 1u) << backend->Name();
    EXPECT_EQ(stats.found, kCells * kPerCell - 2) << backend->Name();
    const std::vector<std::uint32_t>& read =
        backend == &reference ? reference.LastExactResult()->transport_read : backend->LastHashedRun()->transport_read;
    EXPECT_EQ(read[0], kNothingTransported) << backend->Name();
    EXPECT_EQ(read[1], kNothingTransported) << backend->Name();
  }
}

// fixed64's F is chosen by the first frame, which transports nothing, so that two frames like it stay below 2^63: the
// whole batch's sum, twice (core/fixed_point_scale.h). A furnace whose light grows past it (weights of 64: the second
// frame's contributions are 65 times the first's, each still converting) wraps its cells' sums on the second frame,
// and every backend counts the wraps instead of filtering on silently.
TEST(Transport, LightThatOutgrowsTheFirstFramesFIsCounted) {
  FilterConfig config = FurnaceConfig(Accumulation::kFixed64, "integrate", 2);
  ReferenceBackend reference;
  EmulatedBackend emulated{EmulatorOptions{}};
  VulkanBackend vulkan{TestDevice(StagingPolicy::kNever)};
  for (std::uint32_t k = 0; k < 2; ++k) {
    RecordBatch batch = FurnaceBatch(k);
    for (Record& s : batch.scattered) s.throughput = glm::vec4(64.0f, 64.0f, 64.0f, 0.0f);
    config.frame = k;
    reference.FilterFrame(batch, config);
    emulated.FilterFrame(batch, config);
    vulkan.FilterFrame(batch, config);
  }
  EXPECT_GT(reference.LastExactResult()->stats.fixed_point_wraps, 0u);
  EXPECT_EQ(emulated.run().wraps, reference.LastExactResult()->stats.fixed_point_wraps);
  EXPECT_EQ(vulkan.run().wraps, reference.LastExactResult()->stats.fixed_point_wraps);
}

// A firefly fed back: frame 0's record 0 carries 10^4 times e (a path that found a light by chance). The transport
// carries it into the cells whose records scatter into its cell, weighed by the albedo: the excess frame k's records
// bring is at most r = (9/8) a times the excess in the averages they read, with a = 3/4 (green, the largest albedo) and
// 9/8 the most records that scatter into one cell over a cell's records. A table that forgets its history holds frame
// k's alone, so its excess T(k) <= r^k T(0) falls geometrically. An integrating table keeps frame 0's sums, and frame k
// reads them over k + 1 frames' counts: T(k) <= T(k - 1) (1 + r / k), so its sums' excess grows as k^r while the
// cells' averages, and the image, carry T(k) / (k + 1), which falls as k^(r - 1): slower than the 1 / k of a table
// without the transport. Either way it reaches every cell and stays bounded. Measured as the table's sums with the
// firefly less those without it, on the reference, frame by frame; docs/design/algorithm.md has the figures.
TEST(Transport, AFireflyFedBackSpreadsButStaysBounded) {
  constexpr std::uint32_t kFrames = 24;
  const double ratio = 9.0 / 8.0 * double(kAlbedo.y);
  for (const std::string temporal : {"integrate", "ema:0.000000000931322574615478515625"}) {
    const bool integrating = temporal == "integrate";
    const FilterConfig config = FurnaceConfig(Accumulation::kFixed64, temporal, kFrames);
    ReferenceBackend with, without;
    double bound = 0.0, first_average = 0.0;
    std::uint32_t cells_reached = 0;
    for (std::uint32_t k = 0; k < kFrames; ++k) {
      FilterConfig frame_config = config;
      frame_config.frame = k;
      const RecordBatch batch = FurnaceBatch(k);
      RecordBatch bright = batch;
      if (k == 0) bright.records[0].contribution *= 1e4f;
      with.FilterFrame(bright, frame_config);
      without.FilterFrame(batch, frame_config);
      const FilterResult& a = *with.LastExactResult();
      const FilterResult& b = *without.LastExactResult();
      ASSERT_EQ(a.cells.size(), b.cells.size());
      double excess = 0.0, average = 0.0;  // green: in the sums, and in the averages, over the table's cells
      cells_reached = 0;
      for (std::size_t c = 0; c < a.cells.size(); ++c) {
        const double more_average = CellAverage(a.cells[c], Accumulation::kFixed64, a.stats.fixed_point_bits).y -
                                    CellAverage(b.cells[c], Accumulation::kFixed64, b.stats.fixed_point_bits).y;
        const double more =
            CellAverage(a.cells[c], Accumulation::kFixed64, a.stats.fixed_point_bits).y * double(a.cells[c].count) -
            CellAverage(b.cells[c], Accumulation::kFixed64, b.stats.fixed_point_bits).y * double(b.cells[c].count);
        excess += more;
        average += more_average;
        cells_reached += more_average > 1e-6;
      }
      bound = k == 0 ? excess : bound * (integrating ? 1.0 + ratio / double(k) : ratio);
      if (k == 0) first_average = average;
      std::printf(
          "%s, frame %2u: the firefly's excess in the sums %.6g (bound %.6g), in the averages %.6g (%.4f of "
          "frame 0's), %u of %zu cells reached\n",
          temporal.c_str(), k, excess, bound, average, average / first_average, cells_reached, a.cells.size());
      EXPECT_LE(excess, bound * (1.0 + 1e-9)) << temporal << ", frame " << k;
      if (k >= 2) {
        EXPECT_LT(average, first_average) << temporal << ", frame " << k;
      }
    }
    EXPECT_EQ(cells_reached, kCells) << temporal << ": fed back, the firefly reaches every cell";
  }
}

// Deeper records at several levels: the accumulate places every record at each level, level-major over the records
// with the deeper ones, and Vulkan's resolve reads its own records' placements copied out level by level. The
// traced furnace with 3 filtered vertices at 3 levels, over frames: the reference's pixels, bit for bit, on both
// staging policies.
TEST(Transport, VulkanResolvesDeeperRecordsAtSeveralLevels) {
  const std::vector<RecordBatch> frames = TracedFurnaceFrames(3, 3, 16, 2);
  FilterConfig config;
  config.transport = true;
  config.frames = 3;
  config.levels = 3;
  config.min_count = 4;
  config.capacity = 1u << 14;
  ReferenceBackend reference;
  VulkanBackend mapped{TestDevice(StagingPolicy::kNever)};
  VulkanBackend staged{TestDevice(StagingPolicy::kAlways)};
  for (std::uint32_t k = 0; k < config.frames; ++k) {
    config.frame = k;
    ASSERT_FALSE(frames[k].deeper.empty());
    const Image& image = reference.FilterFrame(frames[k], config);
    EXPECT_EQ(mapped.FilterFrame(frames[k], config).pixels, image.pixels) << "frame " << k;
    EXPECT_EQ(staged.FilterFrame(frames[k], config).pixels, image.pixels) << "frame " << k;
    EXPECT_EQ(mapped.run().placements.size(), frames[k].records.size() + frames[k].deeper.size());
  }
}

}  // namespace
}  // namespace hpsf::testing
