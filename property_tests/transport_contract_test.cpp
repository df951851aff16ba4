// The contract over several filtered bounces (verifier/contract/transport_check.h): each frame's transport judged on
// the emulator from its own table before the frame (level 2) and against the reference's reads (level 3), with the
// reads of cells the table could not hold classified and their light's cells classified from then on. Each broken
// transport (emulated/broken_transport.h) fails it. Label `bounces`.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "emulated/defect_injection.h"
#include "emulated/simt/schedule.h"
#include "property_tests/constructed_cells.h"
#include "property_tests/racing_schedules.h"
#include "property_tests/transport_furnace.h"
#include "property_tests/vulkan_test_devices.h"
#include "verifier/contract/contract_levels.h"
#include "verifier/fuzzing/adversarial_case.h"
#include "vulkan/vulkan_backend.h"

namespace hpsf::testing {
namespace {

CrosscheckReport Judge(const std::vector<RecordBatch>& frames, const FilterConfig& config,
                       const EmulatorOptions& emulator) {
  return CrosscheckEmulatedSequence(frames, config, emulator);
}

EmulatorOptions Faithful() {
  EmulatorOptions faithful;
  faithful.mode = simt::Mode::kFaithful;
  faithful.warp_size = 8;
  faithful.schedule = "random:5";
  return faithful;
}

// The synthetic furnace whose light varies from cell to cell, over 6 frames: every level holds on the fast and the
// faithful emulator, in fixed64 and float32, integrating and blending, and nothing is classified (no alias, no
// failure in a table of 1024 slots for 8 cells).
TEST(TransportContract, HoldsFrameByFrameOnTheFurnace) {
  std::vector<RecordBatch> frames;
  for (std::uint32_t k = 0; k < 6; ++k) frames.push_back(FurnaceBatch(k, true));
  for (const Accumulation accumulation : {Accumulation::kFixed64, Accumulation::kFloat32}) {
    for (const std::string temporal : {"integrate", "ema:0.5"}) {
      for (const EmulatorOptions& emulator : {EmulatorOptions{}, Faithful()}) {
        const std::string where = ToString(accumulation) + ", " + temporal + ", " +
                                  (emulator.mode == simt::Mode::kFast ? "fast" : "faithful");
        const CrosscheckReport report = Judge(frames, FurnaceConfig(accumulation, temporal, 6), emulator);
        EXPECT_TRUE(report.Passed()) << where << ": " << report.FirstFailure();
        ASSERT_EQ(report.quality.size(), 1u);
        EXPECT_EQ(report.quality[0].classified_transports, 0u) << where;
      }
    }
  }
}

// The traced furnace with 3 filtered vertices per path (the deeper records in the table, keyed and compared with the
// reference at every level like the records), under level of detail.
TEST(TransportContract, HoldsWithDeeperRecordsOnTheTracedFurnace) {
  FilterConfig config;
  config.transport = true;
  config.frames = 3;
  config.capacity = 1u << 14;
  const CrosscheckReport report = Judge(TracedFurnaceFrames(3, 3, 16, 2), config, EmulatorOptions{});
  EXPECT_TRUE(report.Passed()) << report.FirstFailure();
  EXPECT_EQ(report.quality[0].classified_transports, 0u);
}

// With fingerprints of 8 bits in a table of 512 slots for some 700 cells, cells alias and records fail to probe: a
// transport that reads an aliased slot, or misses a cell the table lost, carries other light than the reference's
// into its record's cells. The contract classifies those reads, and the cells they feed from then on, instead of
// blaming the backend.
TEST(TransportContract, ClassifiesReadsOfCellsTheTableCouldNotHold) {
  FilterConfig config;
  config.transport = true;
  config.frames = 4;
  config.capacity = 512;
  config.fingerprint_bits = 8;
  const CrosscheckReport report = Judge(TracedFurnaceFrames(2, 4, 16, 2), config, EmulatorOptions{});
  EXPECT_TRUE(report.Passed()) << report.FirstFailure();
  EXPECT_GT(report.quality[0].aliased_slots, 0u);
  EXPECT_GT(report.quality[0].classified_transports, 0u);
  std::printf("%s", report.ToText().c_str());
}

// In float32 a slot's sum is held to the exact sum of the records placed in it, the deeper ones included: under
// pressure (256 slots) the traced furnace's deeper records share slots with the pixels' records.
TEST(TransportContract, HoldsInFloat32UnderPressureWithDeeperRecords) {
  FilterConfig config;
  config.transport = true;
  config.frames = 3;
  config.capacity = 256;
  config.fingerprint_bits = 24;
  config.accumulation = Accumulation::kFloat32;
  const CrosscheckReport report = Judge(TracedFurnaceFrames(2, 3, 16, 2), config, EmulatorOptions{});
  EXPECT_TRUE(report.Passed()) << report.FirstFailure();
  EXPECT_GT(report.quality[0].probe_failures, 0u);
}

// Each broken transport fails the contract over the traced furnace's frames, at the level named (reads-current-table in
// fast mode's serial order; the schedules' race is the next test).
TEST(TransportContract, CatchesEachBrokenTransport) {
  const std::vector<RecordBatch> frames = TracedFurnaceFrames(2, 3, 16, 2);
  FilterConfig config;
  config.transport = true;
  config.frames = 3;
  config.capacity = 1u << 14;
  const struct {
    TransportDefect defect;
    int level;  // the first level that fails
  } cases[] = {
      {TransportDefect::kWeightTwice, 2},             // the table's sums are not its transported records'
      {TransportDefect::kScatteredAtRecordLevel, 2},  // a read of another cell than the scattered vertex's
      {TransportDefect::kReadsCurrentTable, 2},       // reads of cells the table before did not hold
  };
  for (const auto& c : cases) {
    EmulatorOptions emulator;
    emulator.transport_defect = c.defect;
    emulator.threads = 1;  // reads-current-table races the frame's adds: fast mode's serial order, the same every run
    const CrosscheckReport report = Judge(frames, config, emulator);
    EXPECT_FALSE(report.Passed()) << ToString(c.defect);
    EXPECT_EQ(report.FirstFailure().rfind("level " + std::to_string(c.level), 0), 0u)
        << ToString(c.defect) << ": " << report.FirstFailure();
    std::printf("%s: %s\n", ToString(c.defect).c_str(), report.FirstFailure().c_str());
  }
}

// reads-current-table looks each record's scattered vertex up inside the accumulate's launch, in the table it adds to
// (TransportDuringAccumulate): what it reads depends on which of the frame's adds came first. Over the traced
// furnace's 3 frames at 8 x 8 pixels, the faithful emulator explores 40 schedules (random and PCT of depth 3, warps
// of 4) and fast mode's serial order; the correct transport passes under every one, the race is caught under some.
TEST(TransportContract, AReadOfTheCurrentTableIsARaceTheSchedulesFind) {
  const std::vector<RecordBatch> frames = TracedFurnaceFrames(2, 3, 8, 2);
  FilterConfig config;
  config.transport = true;
  config.frames = 3;
  config.capacity = 1u << 12;
  const std::vector<EmulatorOptions> schedules = RacingSchedules();
  int caught = 0;
  for (EmulatorOptions options : schedules) {
    const std::string name = options.mode == simt::Mode::kFast ? "fast, one thread" : options.schedule;
    const CrosscheckReport correct = Judge(frames, config, options);
    EXPECT_TRUE(correct.Passed()) << name << ": " << correct.FirstFailure();
    options.transport_defect = TransportDefect::kReadsCurrentTable;
    const CrosscheckReport racing = Judge(frames, config, options);
    if (!racing.Passed() && caught++ == 0) std::printf("%s: %s\n", name.c_str(), racing.FirstFailure().c_str());
  }
  std::printf("a transport reading the current table: caught under %d of %zu schedules\n", caught, schedules.size());
  EXPECT_GT(caught, 0);
}

// Every order of one record's read of cell A and another record's add to A, enumerated. Frame 0 places A (one
// record, 1.0); in frame 1, thread 0 (a record of cell B) scatters into A and thread 1 adds a record of 1.25 to A.
// The exhaustive schedule (warps of one lane) runs every order of the two threads' operations. The race reads A's
// history only where all of thread 1's adds to A come after thread 0's reads of them; any other order carries the
// frame's own light (or a torn sum and count) into B. The oracle is the correct transport's table, the same bits
// under every schedule; it passes every order.
TEST(TransportContract, EveryOrderOfAReadAndAnAddToItsCellIsExplored) {
  FilterConfig config = ConstructedConfig(8, 4);
  config.transport = true;
  config.frames = 2;
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 0u; });
  const glm::ivec3 b = FindCell(config, [](const KeyResult& k) { return k.slot0 == 4u; });
  const RecordBatch frame0 = BatchOfCells({a});
  RecordBatch frame1 = BatchOfCells({b, a});  // contributions 1.0 and 1.25
  frame1.frame = 1;
  frame1.scattered = {frame1.records[1], frame1.records[1]};
  frame1.scattered[1].path.z &= ~shared::kRecordHasVertex;  // thread 1's path scattered nowhere
  const EmulatedRun first = EmulatedFilter(frame0, config, EmulatorOptions{});
  config.frame = 1;
  const EmulatedRun expected = EmulatedFilter(frame1, config, EmulatorOptions{}, AccumulateKernel, &first.table);
  ASSERT_EQ(expected.transport.found, 1u);
  auto explore = [&](TransportDefect defect) {
    EmulatorOptions options;
    options.transport_defect = defect;
    return ExploreEveryOrder(options, [&](const EmulatorOptions& each) {
      return EmulatedFilter(frame1, config, each, AccumulateKernel, &first.table).table.fixed_sums !=
             expected.table.fixed_sums;
    });
  };
  const Exploration correct = explore(TransportDefect::kNone);
  const Exploration racing = explore(TransportDefect::kReadsCurrentTable);
  std::printf(
      "one read and one add to its cell, exhaustive: correct transport %llu schedules, all equal; reading the current "
      "table caught under %llu of %llu\n",
      (unsigned long long)correct.schedules, (unsigned long long)racing.caught, (unsigned long long)racing.schedules);
  EXPECT_EQ(correct.caught, 0u);
  EXPECT_GT(racing.caught, 0u);
  EXPECT_LT(racing.caught, racing.schedules) << "no order read A's history: the exploration saw no order that does";
}

// A team's transport shader (--transport-spv), given through the interface of transport.comp, on Vulkan mapped and
// staged over the traced furnace's 3 frames: hpsf's own shader given as a team's holds the contract; one that applies
// the scattered vertex's throughput twice fails level 2 at a slot's sums, and one that writes back a slot past the
// table fails level 2 naming the record and the word.
TEST(TransportContract, ATeamsTransportShaderIsJudgedByTheContract) {
  const std::vector<RecordBatch> frames = TracedFurnaceFrames(2, 3, 16, 2);
  FilterConfig config;
  config.transport = true;
  config.frames = 3;
  config.capacity = 1u << 14;
  std::vector<std::uint32_t> numbers;
  for (const RecordBatch& batch : frames) numbers.push_back(batch.frame);
  const struct {
    const char* variant;
    const char* failure;  // what the first failure says; empty where the contract holds
  } cases[] = {
      {"correct", ""},
      {"WEIGHT_TWICE", "sum differs from the records placed at slot"},
      {"READ_PAST_THE_END", "invalid shader output: record 0: transport read 16384, not a slot below the capacity"},
  };
  for (const StagingPolicy staging : kStagingPolicies) {
    for (const auto& c : cases) {
      const std::string spv = std::string(HPSF_SHADER_VARIANT_DIR "/transport_") + c.variant + ".spv";
      VulkanBackend backend(TestDevice(staging), "", "", "", "", "", spv);
      VulkanBackend rerun(TestDevice(staging), "", "", "", "", "", spv);
      const JudgedBackend judged{"vulkan", &backend, &rerun, "rerun", false, true};
      const CrosscheckReport report =
          JudgeSequence(frames, numbers, config, std::span<const JudgedBackend>(&judged, 1));
      const std::string name = std::string(c.variant) + ", staging " + ToString(staging);
      if (std::string(c.failure).empty()) {
        EXPECT_TRUE(report.Passed()) << name << ": " << report.FirstFailure();
        continue;
      }
      EXPECT_FALSE(report.Passed()) << name;
      EXPECT_EQ(report.FirstFailure().rfind("level 2", 0), 0u) << name << ": " << report.FirstFailure();
      EXPECT_NE(report.FirstFailure().find(c.failure), std::string::npos) << name << ": " << report.FirstFailure();
      std::printf("%s: %s\n", name.c_str(), report.FirstFailure().c_str());
    }
  }
}

// hpsf fuzz's sequences that transport (verifier/fuzzing/adversarial_case.h) have teeth: over the first 30 of seed 1,
// the correct transport passes every one, and each broken transport fails some.
TEST(TransportContract, TheFuzzersSequencesCatchEachBrokenTransport) {
  std::vector<AdversarialCase> cases;
  for (std::uint64_t run = 0; cases.size() < 30; ++run) {
    AdversarialCase c = MakeAdversarialCase(1, run);
    if (c.config.transport) cases.push_back(std::move(c));
  }
  for (const TransportDefect defect : {TransportDefect::kNone, TransportDefect::kWeightTwice,
                                       TransportDefect::kScatteredAtRecordLevel, TransportDefect::kReadsCurrentTable}) {
    int failed = 0;
    for (const AdversarialCase& c : cases) {
      EmulatorOptions emulator = c.emulator;
      emulator.transport_defect = defect;
      if (emulator.mode == simt::Mode::kFast) emulator.threads = 1;  // the race's reads in one order every run
      failed += !Judge(c.Frames(), c.config, emulator).Passed();
    }
    std::printf("%s: %d of %zu sequences fail\n", ToString(defect).c_str(), failed, cases.size());
    if (defect == TransportDefect::kNone) {
      EXPECT_EQ(failed, 0);
    } else {
      EXPECT_GT(failed, 0) << ToString(defect);
    }
  }
}

}  // namespace
}  // namespace hpsf::testing
