#include "emulated/emulated_filter.h"

#include <array>
#include <bit>
#include <cmath>
#include <optional>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "core/footprint.h"
#include "core/input_check.h"
#include "core/resolve.h"

namespace hpsf {

void EmulatorOptions::Validate() const {
  if (warp_size == 0 || warp_size > 1024) throw ConfigError("--warp-size", "must lie in [1, 1024]; got " + std::to_string(warp_size));
  if (threads < 0) throw ConfigError("--threads", "must be >= 0 (0: all cores)");
  if (mode == simt::Mode::kFaithful) simt::MakeSchedule(schedule, 1, 1);  // parses, or names --schedule
}

EmulatedRun EmulatedFilter(const RecordBatch& batch, const FilterConfig& config, const EmulatorOptions& options,
                           AccumulateKernelFn accumulate) {
  CheckBatchShape(batch);
  config.Validate();
  options.Validate();
  const std::uint32_t n = static_cast<std::uint32_t>(batch.records.size());
  const KeyParams params = MakeKeyParams(config, FootprintScale(config.filter_width_px, batch.fov_y_radians, batch.height), n);

  EmulatedRun run;
  // Keys on all cores: each is a function of its record alone.
  run.keys.resize(n);
  std::vector<std::uint8_t> accepted(n);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, n, 4096), [&](const tbb::blocked_range<std::uint32_t>& range) {
    for (std::uint32_t i = range.begin(); i < range.end(); ++i) {
      run.keys[i] = shared::ComputeKey(params, batch.records[i]);
      accepted[i] = CheckRecordInputs(batch.records[i]) == InputVerdict::kAccepted;
    }
  });

  HashTableDump& table = run.table;
  table.capacity = config.capacity;
  table.probe_limit = config.probe_limit;
  table.fingerprint_bits = config.fingerprint_bits;
  table.accumulation = config.accumulation;
  table.fixed_point_bits = ChooseFixedPointBits(batch.records);
  const bool fixed = config.accumulation == Accumulation::kFixed64;

  simt::DeviceMemory memory;
  AccumulateArgs args;
  args.records = batch.records;
  args.keys = run.keys;
  args.accepted = accepted;
  args.capacity = config.capacity;
  args.probe_limit = config.probe_limit;
  args.accumulation = config.accumulation;
  args.fixed_point_scale = shared::PowerOfTwo(table.fixed_point_bits);
  TableBuffers& b = args.buffers;
  b.tags = memory.Allocate32("tags", config.capacity);
  b.sums = fixed ? memory.Allocate64("sums", std::size_t(config.capacity) * 3) : memory.Allocate32("sums", std::size_t(config.capacity) * 3);
  b.counts = memory.Allocate64("counts", config.capacity);
  b.placements = memory.Allocate32("placements", n);
  b.wraps = memory.Allocate64("wraps", 1);

  const simt::Kernel kernel = [&](simt::ThreadContext& ctx) { return accumulate(ctx, args); };
  if (options.mode == simt::Mode::kFast) {
    simt::LaunchFast(memory, n, kernel, options.threads);
  } else {
    const std::uint32_t warps = (n + options.warp_size - 1) / options.warp_size;
    auto schedule = simt::MakeSchedule(options.schedule, warps, std::uint64_t(warps) * (2 * config.probe_limit + 6));
    simt::OperationObserver observer;
    if (!fixed) {
      run.float_add_order.resize(std::size_t(config.capacity) * 3);
      observer = [&](std::uint32_t thread, const simt::MemoryOp& op) {
        if (op.kind == simt::OpKind::kAtomicAddFloat && op.address.buffer == b.sums) run.float_add_order[op.address.index].push_back(thread);
      };
    }
    run.launch = simt::LaunchFaithful(memory, n, options.warp_size, kernel, *schedule, observer);
  }

  // The dump: the final state of the device buffers.
  const auto tags = memory.Words32(b.tags);
  table.tags.assign(tags.begin(), tags.end());
  table.counts.assign(memory.Words64(b.counts).begin(), memory.Words64(b.counts).end());
  if (fixed) {
    table.fixed_sums.resize(config.capacity);
    const auto sums = memory.Words64(b.sums);
    for (std::uint32_t s = 0; s < config.capacity; ++s) table.fixed_sums[s] = {sums[3 * s], sums[3 * s + 1], sums[3 * s + 2]};
  } else {
    table.float_sums.resize(config.capacity);
    const auto sums = memory.Words32(b.sums);
    for (std::uint32_t s = 0; s < config.capacity; ++s) {
      for (int c = 0; c < 3; ++c) table.float_sums[s][c] = std::bit_cast<float>(sums[3 * s + c]);
    }
  }
  run.placements.assign(memory.Words32(b.placements).begin(), memory.Words32(b.placements).end());
  run.wraps = memory.Words64(b.wraps)[0];

  // Probe lengths follow from the placements; resolve uses each placed record's slot average.
  run.probe_lengths.assign(config.probe_limit, 0);
  std::vector<std::optional<glm::dvec3>> averages(n);
  const double unscale = std::ldexp(1.0, -table.fixed_point_bits);  // exact, as FromFixedPoint, without a call per sum
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t slot = run.placements[i];
    if (slot == kProbeFailure) ++run.probe_failures;
    if (slot >= config.capacity) continue;
    ++run.probe_lengths[(slot - run.keys[i].slot0) & (config.capacity - 1u)];
    glm::dvec3 average;
    for (int c = 0; c < 3; ++c) {
      const double sum = fixed ? double(table.fixed_sums[slot][c]) * unscale : double(table.float_sums[slot][c]);
      average[c] = sum / double(table.counts[slot]);
    }
    averages[i] = average;
  }
  run.image = ResolvePixels(batch, averages);
  return run;
}

std::vector<bool> AliasedSlots(const EmulatedRun& run) {
  std::vector<std::optional<std::array<std::uint32_t, 6>>> key_of(run.table.capacity);
  std::vector<bool> aliased(run.table.capacity, false);
  for (std::size_t i = 0; i < run.placements.size(); ++i) {
    const std::uint32_t slot = run.placements[i];
    if (slot >= run.table.capacity) continue;
    const shared::KeyWords& w = run.keys[i].words;
    const std::array<std::uint32_t, 6> key = {w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra};
    if (key_of[slot] && *key_of[slot] != key) aliased[slot] = true;
    key_of[slot] = key;
  }
  return aliased;
}

}  // namespace hpsf
