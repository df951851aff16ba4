// The gate has teeth: broken variants of the accumulate kernel, one per known defect of DESIGN.md (D2, D3, D8,
// D9, D13), run on inputs constructed to reach the defect. For each, the table checker or the cross-check
// contract must fail. D9 and D13 need a particular interleaving: the tests report which schedule policies found
// them and after how many schedules.
#include <bit>
#include <cstdio>
#include <optional>

#include <gtest/gtest.h>

#include "core/hash_table.h"
#include "core/input_check.h"
#include "core/shared/fixed_point.h"
#include "emulated/emulated_filter.h"
#include "tools/checks/table_checker.h"

namespace hpsf {
namespace {

enum class Defect { kD2AddsAgain, kD3ZeroFingerprint, kD8ClampedProbe, kD9NonAtomicAdd, kD13LoadThenStoreClaim };

// The correct kernel (emulated/accumulate_kernel.cpp) with exactly one defect switched in.
simt::KernelTask Mutant(simt::ThreadContext& ctx, const AccumulateArgs& args, Defect defect) {
  const std::uint32_t i = ctx.Thread();
  const KeyResult& key = args.keys[i];
  const TableBuffers& b = args.buffers;
  if (!args.accepted[i] || key.status != shared::kKeyed) {
    co_await ctx.Store(b.placements, i, kNotPlaced);
    co_return;
  }
  // D3: the reduced fingerprint without its 0 -> 1 fix.
  const std::uint32_t fingerprint =
      defect == Defect::kD3ZeroFingerprint ? shared::FullFingerprint(key.words) >> 24 : key.fingerprint;
  const Record& r = args.records[i];
  bool placed = false;
  for (std::uint32_t probe = 0; probe < args.probe_limit; ++probe) {
    // D8: the probe index clamped to the last slot instead of wrapped.
    const std::uint32_t slot = defect == Defect::kD8ClampedProbe ? std::min(key.slot0 + probe, args.capacity - 1u)
                                                                 : (key.slot0 + probe) & (args.capacity - 1u);
    std::uint64_t tag = co_await ctx.Load(b.tags, slot);
    if (tag == kEmptyTag) {
      if (defect == Defect::kD13LoadThenStoreClaim) {  // D13: claim by a plain store after the load
        co_await ctx.Store(b.tags, slot, fingerprint);
      } else {
        tag = co_await ctx.AtomicCas(b.tags, slot, kEmptyTag, fingerprint);
      }
    }
    if (tag != kEmptyTag && tag != fingerprint) continue;
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t add = shared::ToFixedPoint(r.contribution[c], args.fixed_point_scale);
      if (defect == Defect::kD9NonAtomicAdd) {  // D9: read-modify-write without an atomic
        const std::uint64_t old = co_await ctx.Load(b.sums[c], slot);
        co_await ctx.Store(b.sums[c], slot, old + add);
      } else {
        co_await ctx.AtomicAdd(b.sums[c], slot, add);
      }
    }
    if (defect == Defect::kD9NonAtomicAdd) {
      const std::uint64_t count = co_await ctx.Load(b.counts, slot);
      co_await ctx.Store(b.counts, slot, count + 1);
    } else {
      co_await ctx.AtomicAdd(b.counts, slot, 1);
    }
    co_await ctx.Store(b.placements, i, slot);
    placed = true;
    if (defect != Defect::kD2AddsAgain) co_return;  // D2: keeps probing and adds again (Meijer Algorithm 4)
  }
  if (!placed) co_await ctx.Store(b.placements, i, kProbeFailure);
}

simt::KernelTask D2(simt::ThreadContext& c, const AccumulateArgs& a) { return Mutant(c, a, Defect::kD2AddsAgain); }
simt::KernelTask D3(simt::ThreadContext& c, const AccumulateArgs& a) { return Mutant(c, a, Defect::kD3ZeroFingerprint); }
simt::KernelTask D8(simt::ThreadContext& c, const AccumulateArgs& a) { return Mutant(c, a, Defect::kD8ClampedProbe); }
simt::KernelTask D9(simt::ThreadContext& c, const AccumulateArgs& a) { return Mutant(c, a, Defect::kD9NonAtomicAdd); }
simt::KernelTask D13(simt::ThreadContext& c, const AccumulateArgs& a) { return Mutant(c, a, Defect::kD13LoadThenStoreClaim); }

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
  const auto violations = CheckRun(batch, RunFaithful(batch, config, D2));
  ASSERT_FALSE(violations.empty());
  std::printf("D2 caught: %s\n", violations.front().ToString().c_str());
}

TEST(BrokenKernels, D3AZeroFingerprintIsCaught) {
  // A key whose 8-bit fingerprint reduces to 0: the mutant "claims" its slot with the empty tag.
  const FilterConfig config = ConstructedConfig(64, 4, 8);
  const glm::ivec3 zero = FindCell(config, [](const KeyResult& k) { return (shared::FullFingerprint(k.words) >> 24) == 0u; });
  const RecordBatch batch = BatchOfCells({zero, zero});
  const auto violations = CheckRun(batch, RunFaithful(batch, config, D3));
  ASSERT_FALSE(violations.empty());
  std::printf("D3 caught: %s\n", violations.front().ToString().c_str());
}

TEST(BrokenKernels, D8AClampedProbeIsCaught) {
  // Keys whose window wraps past capacity - 1: two keys at slot0 = 63 make the second probe.
  const FilterConfig config = ConstructedConfig(64, 4);
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 63u; });
  const glm::ivec3 b = FindCell(config, [](const KeyResult& k) { return k.slot0 == 63u; }, a.x + 1);
  const RecordBatch batch = BatchOfCells({a, b});
  const auto violations = CheckRun(batch, RunFaithful(batch, config, D8));
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
  Report("D9", HuntDefect(batch, config, D9, 1));
  // Within one warp the lanes load together and store in turn: every schedule loses updates.
  EXPECT_FALSE(CheckRun(batch, RunFaithful(batch, config, D9, "round-robin", 8)).empty());
}

TEST(BrokenKernels, D13TwoKeysRacingForOneEmptySlotAreCaughtAndReportedPerPolicy) {
  const FilterConfig config = ConstructedConfig(64, 4);
  const glm::ivec3 a = FindCell(config, [](const KeyResult& k) { return k.slot0 == 17u; });
  const glm::ivec3 b = FindCell(config, [](const KeyResult& k) { return k.slot0 == 17u; }, a.x + 1);
  const RecordBatch batch = BatchOfCells({a, b, a, b});
  Report("D13", HuntDefect(batch, config, D13, 1));
}

}  // namespace
}  // namespace hpsf
