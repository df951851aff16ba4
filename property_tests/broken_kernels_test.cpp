// The gate has teeth: the broken variants of the accumulate kernel (emulated/defect_injection), one per known
// defect of DESIGN.md (D2, D3, D8, D9, D13), run on inputs constructed to reach the defect. For each, the table
// checker or the cross-check contract must fail. D9 and D13 need a particular interleaving: the tests report
// which schedule policies found them and after how many schedules.
#include <bit>
#include <cstdio>
#include <optional>

#include <gtest/gtest.h>

#include "core/hash_table.h"
#include "core/input_check.h"
#include "emulated/defect_injection.h"
#include "emulated/emulated_filter.h"
#include "tools/checks/table_checker.h"

namespace hpsf {
namespace {

// Keys chosen by cell: level of detail off, unit cells, no jitter, no normal bucket, so a record at
// (x + 0.5, y + 0.5, z + 0.5) has the cell (x, y, z) and everything about its key is known in advance.
FilterConfig ConstructedConfig(std::uint32_t capacity, std::uint32_t probe_limit, std::uint32_t fingerprint_bits = 32) {
  FilterConfig c;
  c.lod = false;
  c.cell_size = 1.0f;
  c.jitter_scale = 0.0f;
  c.normal = {NormalMode::kNone, 0};
  c.capacity = capacity;
  c.probe_limit = probe_limit;
  c.fingerprint_bits = fingerprint_bits;
  return c;
}

KeyResult KeyOfCell(const FilterConfig& config, glm::ivec3 cell) {
  VertexSample v;
  v.position = glm::vec3(cell) + glm::vec3(0.5f);
  v.previous = v.position + glm::vec3(0.0f, 0.0f, -10.0f);
  return shared::ComputeKey(MakeKeyParams(config, 0.01f, 1), MakeVertexRecord(v));
}

RecordBatch BatchOfCells(const std::vector<glm::ivec3>& cells) {
  RecordBatch batch;
  batch.width = static_cast<std::uint32_t>(cells.size());
  batch.height = 1;
  batch.samples_per_pixel = 1;
  batch.fov_y_radians = 0.5;
  for (std::uint32_t i = 0; i < cells.size(); ++i) {
    VertexSample v;
    v.pixel = i;
    v.position = glm::vec3(cells[i]) + glm::vec3(0.5f);
    v.previous = v.position + glm::vec3(0.0f, 0.0f, -10.0f);
    v.contribution = glm::vec3(1.0f + 0.25f * float(i % 7), 0.5f, 0.125f);
    v.throughput = glm::vec3(0.5f);
    batch.records.push_back(MakeVertexRecord(v));
  }
  return batch;
}

// The first cell along x (from `start`) whose key satisfies `wanted`.
glm::ivec3 FindCell(const FilterConfig& config, const std::function<bool(const KeyResult&)>& wanted, int start = 0) {
  for (int x = start; x < start + 2000000; ++x) {
    if (wanted(KeyOfCell(config, {x, 3, -7}))) return {x, 3, -7};
  }
  ADD_FAILURE() << "no cell found";
  return {0, 0, 0};
}

std::vector<TableViolation> CheckRun(const RecordBatch& batch, const EmulatedRun& run) {
  return CheckTable({run.table, batch.records, run.keys, run.placements});
}

EmulatedRun RunFaithful(const RecordBatch& batch, const FilterConfig& config, AccumulateKernelFn kernel,
                        const std::string& schedule = "round-robin", std::uint32_t warp_size = 8) {
  EmulatorOptions options;
  options.mode = simt::Mode::kFaithful;
  options.warp_size = warp_size;
  options.schedule = schedule;
  return EmulatedFilter(batch, config, options, kernel);
}

TEST(BrokenKernels, CorrectKernelPassesOnEveryConstructedInput) {
  const FilterConfig config = ConstructedConfig(64, 4, 8);
  const glm::ivec3 zero = FindCell(config, [](const KeyResult& k) { return (shared::FullFingerprint(k.words) >> 24) == 0u; });
  const glm::ivec3 last = FindCell(config, [](const KeyResult& k) { return k.slot0 == 63u; });
  const RecordBatch batch = BatchOfCells({zero, zero, last, last, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}});
  EXPECT_TRUE(CheckRun(batch, RunFaithful(batch, config, AccumulateKernel)).empty());
}

TEST(BrokenKernels, D2AddingAgainAfterAMatchIsCaught) {
  const FilterConfig config = ConstructedConfig(64, 4);
  const RecordBatch batch = BatchOfCells({{1, 2, 3}, {1, 2, 3}, {9, 9, 9}});
  const auto violations = CheckRun(batch, RunFaithful(batch, config, KernelWithDefect(Defect::kD2AddsAgain)));
  ASSERT_FALSE(violations.empty());
  std::printf("D2 caught: %s\n", violations.front().ToString().c_str());
}

TEST(BrokenKernels, D3AZeroFingerprintIsCaught) {
  // A key whose 8-bit fingerprint reduces to 0: the mutant "claims" its slot with the empty tag.
  const FilterConfig config = ConstructedConfig(64, 4, 8);
  const glm::ivec3 zero = FindCell(config, [](const KeyResult& k) { return (shared::FullFingerprint(k.words) >> 24) == 0u; });
  const RecordBatch batch = BatchOfCells({zero, zero});
  const auto violations = CheckRun(batch, RunFaithful(batch, config, KernelWithDefect(Defect::kD3ZeroFingerprint)));
  ASSERT_FALSE(violations.empty());
  std::printf("D3 caught: %s\n", violations.front().ToString().c_str());
}

TEST(BrokenKernels, D8AClampedProbeIsCaught) {
  // Keys whose window wraps past capacity - 1: two keys at slot0 = 63 make the second probe.
  const FilterConfig config = ConstructedConfig(64, 4);
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 63u; });
  const glm::ivec3 b = FindCell(config, [](const KeyResult& k) { return k.slot0 == 63u; }, a.x + 1);
  const RecordBatch batch = BatchOfCells({a, b});
  const auto violations = CheckRun(batch, RunFaithful(batch, config, KernelWithDefect(Defect::kD8ClampedProbe)));
  ASSERT_FALSE(violations.empty());
  std::printf("D8 caught: %s\n", violations.front().ToString().c_str());
}

// D9 and D13 depend on the interleaving: try each policy over seeds and report after how many schedules it
// first produced a table the checker rejects.
struct Hunt {
  std::string policy;
  int schedules_until_caught = -1;  // -1: not caught within the budget
};

std::vector<Hunt> HuntDefect(const RecordBatch& batch, const FilterConfig& config, AccumulateKernelFn kernel, std::uint32_t warp_size) {
  std::vector<Hunt> hunts;
  auto caught = [&](const std::string& schedule) { return !CheckRun(batch, RunFaithful(batch, config, kernel, schedule, warp_size)).empty(); };
  hunts.push_back({"round-robin", caught("round-robin") ? 1 : -1});
  for (const std::string family : {"random", "pct:2", "pct:3"}) {
    Hunt hunt{family, -1};
    for (int seed = 0; seed < 200 && hunt.schedules_until_caught < 0; ++seed) {
      const std::string schedule = family == "random" ? "random:" + std::to_string(seed)
                                                      : "pct:" + std::to_string(seed) + family.substr(3);
      if (caught(schedule)) hunt.schedules_until_caught = seed + 1;
    }
    hunts.push_back(hunt);
  }
  return hunts;
}

void Report(const char* defect, const std::vector<Hunt>& hunts) {
  bool any = false;
  for (const Hunt& h : hunts) {
    std::printf("%s with %-11s: %s\n", defect, h.policy.c_str(),
                h.schedules_until_caught < 0 ? "not caught in 200 schedules" : ("caught after " + std::to_string(h.schedules_until_caught) + " schedule(s)").c_str());
    any = any || h.schedules_until_caught > 0;
  }
  EXPECT_TRUE(any) << defect << " escaped every policy";
}

TEST(BrokenKernels, D9LostUpdatesAreCaughtAndReportedPerPolicy) {
  // Eight records of one cell in different warps (warp size 1): their load-then-store adds can interleave.
  const FilterConfig config = ConstructedConfig(64, 4);
  const RecordBatch batch = BatchOfCells(std::vector<glm::ivec3>(8, glm::ivec3(5, 5, 5)));
  Report("D9", HuntDefect(batch, config, KernelWithDefect(Defect::kD9NonAtomicAdd), 1));
  // Within one warp the lanes load together and store in turn: every schedule loses updates.
  EXPECT_FALSE(CheckRun(batch, RunFaithful(batch, config, KernelWithDefect(Defect::kD9NonAtomicAdd), "round-robin", 8)).empty());
}

TEST(BrokenKernels, D13TwoKeysRacingForOneEmptySlotAreCaughtAndReportedPerPolicy) {
  const FilterConfig config = ConstructedConfig(64, 4);
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 17u; });
  const glm::ivec3 b = FindCell(config, [](const KeyResult& k) { return k.slot0 == 17u; }, a.x + 1);
  const RecordBatch batch = BatchOfCells({a, b, a, b});
  Report("D13", HuntDefect(batch, config, KernelWithDefect(Defect::kD13LoadThenStoreClaim), 1));
}

}  // namespace
}  // namespace hpsf
