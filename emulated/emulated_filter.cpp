#include "emulated/emulated_filter.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <memory>
#include <utility>

#include "core/count_words.h"
#include "core/error.h"
#include "core/fixed_point_scale.h"
#include "core/footprint.h"
#include "core/huge_pages.h"
#include "core/input_check.h"
#include "core/parallel_for.h"
#include "core/prefetch.h"
#include "core/resolve.h"
#include "core/shared/levels.h"
#include "core/shared/packed_sums.h"
#include "core/temporal.h"
#include "core/transport.h"
#include "emulated/compaction_kernels.h"
#include "emulated/defect_injection.h"
#include "emulated/level_seed_kernel.h"
#include "emulated/packed_settle_kernel.h"
#include "emulated/temporal_kernel.h"

namespace hpsf {
namespace {

// F's passes over the contributions on all cores (core has no thread pool of its own).
void AllCores(std::size_t n, const std::function<void(std::size_t, std::size_t)>& work) {
  ParallelFor(n, std::size_t(1) << 16, work);
}

class PhaseClock {
 public:
  // Milliseconds since the previous lap.
  double LapMs() {
    const auto now = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::milli>(now - std::exchange(last_, now)).count();
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

void EmulatorOptions::Validate() const {
  if (warp_size == 0 || warp_size > 1024)
    throw ConfigError("--warp-size", "must lie in [1, 1024]; got " + std::to_string(warp_size));
  if (threads < 0) throw ConfigError("--threads", "must be >= 0 (0: all cores)");
  if (mode == simt::Mode::kFaithful) simt::MakeSchedule(schedule, 1, 1);  // parses, or names --schedule
  if (!(spurious_cas >= 0.0 && spurious_cas < 1.0)) {
    throw ConfigError("--spurious-cas", "must lie in [0, 1); got " + std::to_string(spurious_cas));
  }
  if (spurious_cas > 0.0 && mode != simt::Mode::kFaithful) {
    throw ConfigError("--spurious-cas",
                      "needs --mode faithful: fast mode runs the CPU's compare-and-swap, which never "
                      "fails spuriously on x86");
  }
}

EmulatedRun EmulatedFilter(const RecordBatch& given, const FilterConfig& config, const EmulatorOptions& options,
                           AccumulateKernelFn accumulate, const HashTableDump* previous,
                           EvictionKernels eviction_kernels, const FrameEffects* effects,
                           EmulatorWorkspace* workspace) {
  CheckBatchShape(given);
  CheckScatteredShape(given);
  config.Validate();
  options.Validate();
  const KeyParams params =
      MakeKeyParams(config, FootprintScale(config.filter_width_px, given.fov_y_radians, given.height),
                    static_cast<std::uint32_t>(given.records.size() + given.deeper.size()));

  EmulatorWorkspace scratch;  // a run without a workspace: fresh arrays
  EmulatorWorkspace& kept = workspace ? *workspace : scratch;
  EmulatedRun run;
  PhaseClock clock;
  // Several filtered bounces: a host pass over the table before the frame on the fast mode's workers, which no launch
  // of the frame writes, so no schedule can change what it reads. reads-current-table instead transports inside the
  // accumulate's launch (TransportDuringAccumulate), racing the frame's adds.
  std::optional<TransportResult> transport;
  // Without a table before the frame (the first, where the transport is forced) every lookup misses.
  const bool transporting = effects ? effects->transport : previous && PlanFrameEffects(config, kLaterFrame).transport;
  const TransportDefect defect = options.transport_defect;
  const bool transport_in_pass = transporting && defect == TransportDefect::kReadsCurrentTable;
  if (transporting && !transport_in_pass) {
    const TransportLookup lookup = [&](const shared::KeyWords& w) -> std::optional<FoundCell> {
      const std::optional<std::uint32_t> slot =
          previous ? FindSlotInTable(*previous, w, config.normal_in_index) : std::nullopt;
      if (!slot) return std::nullopt;
      return FoundCell{*slot, StateOfSlot(*previous, *slot)};
    };
    // On the fast mode's workers: each record's lookup reads the dump alone.
    const RangeLoop on_workers = [&](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body) {
      ParallelFor(count, 4096, body, options.threads);
    };
    // Bound by reference: a conditional of the copy and `given` would copy the whole batch for the correct pass too.
    std::optional<RecordBatch> weighted_twice;
    if (defect == TransportDefect::kWeightTwice) weighted_twice = WithWeightTwice(given);
    transport =
        TransportBatch(weighted_twice ? *weighted_twice : given, params, config.accumulation,
                       previous ? previous->fixed_point_bits : 0, lookup,
                       defect == TransportDefect::kScatteredAtRecordLevel ? KeyAtRecordLevel : nullptr, on_workers);
    run.transport_read = std::move(transport->read);
    run.transport = transport->stats;
    run.timings.transport_ms = clock.LapMs();
  }
  const RecordBatch& batch = transport ? transport->batch : given;
  const TableRecords table_records(batch);  // the records then the deeper ones; only the records are resolved
  const std::span<const Record> all = table_records.all();
  const std::uint32_t n = static_cast<std::uint32_t>(all.size());
  // Keys on all cores: each is a function of its record alone.
  // The same pass notes which records pass the input checks and gathers, for F, the contributions of those
  // that enter the table.
  run.keys = ReuseForOverwrite(kept.keys, n);
  std::vector<std::uint8_t> accepted = ReuseForOverwrite(kept.accepted, n);
  std::vector<glm::vec3> entering = ReuseForOverwrite(kept.entering, n);
  ParallelFor(n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Record& r = all[i];
      run.keys[i] = shared::ComputeKey(params, r);
      accepted[i] = CheckRecordInputs(r) == InputVerdict::kAccepted;
      entering[i] = accepted[i] && shared::RecordHasVertex(r) ? glm::vec3(r.contribution) : glm::vec3(0.0f);
    }
  });

  run.timings.keys_ms = clock.LapMs();
  HashTableDump& table = run.table;
  table.capacity = config.capacity;
  table.probe_limit = config.probe_limit;
  table.probing = config.probing;
  table.fingerprint_bits = config.fingerprint_bits;
  table.key_identity = config.key_identity;
  table.accumulation = config.accumulation;
  table.levels = config.levels;
  const bool packed = config.accumulation == Accumulation::kPackedDecimal;  // SHaRC's layout, F unused
  table.fixed_point_bits = packed                    ? 0
                           : previous                ? previous->fixed_point_bits
                           : config.fixed_point_bits ? *config.fixed_point_bits
                                                     : ChooseFixedPointBitsOf(entering, AllCores, config.SumHeadroom());
  const bool fixed = IntegerSums(config.accumulation);  // fixed64 or packed-decimal
  const bool wide_sums = config.accumulation == Accumulation::kFixed64;
  if (config.accumulation == Accumulation::kFloat32) RequireFloat32Range(table.fixed_point_bits);
  if (wide_sums) RequireFixedPointConverts(entering, table.fixed_point_bits);
  if (packed) RequirePackedDecimalConverts(entering);
  table.second_moments = config.second_moments;
  if (config.second_moments) {
    table.square_bits = previous             ? previous->square_bits
                        : config.square_bits ? *config.square_bits
                                             : ChooseSquareBitsOf(entering, AllCores, config.SquareHeadroom());
    if (wide_sums) RequireSquaresConvert(entering, table.square_bits);
    if (!fixed) RequireFloat32SquaresRange(table.square_bits);
  }

  run.timings.fixed_point_ms = clock.LapMs();
  simt::DeviceMemory memory;
  AccumulateArgs args;
  args.records = all;
  args.keys = run.keys;
  args.key_params = params;
  args.levels = config.levels;
  args.accepted = accepted;
  args.capacity = config.capacity;
  args.probe_limit = config.probe_limit;
  args.probing = config.probing;
  args.fingerprint_bits = config.fingerprint_bits;
  args.accumulation = config.accumulation;
  args.fixed_point_scale = SumScale(config.accumulation, table.fixed_point_bits);
  TableBuffers& b = args.buffers;
  // A fingerprint fits 32 bits, a full key needs 64 (core/key_identity.h).
  const bool full_keys = config.key_identity == KeyIdentity::kFull;
  b.tags = full_keys ? memory.Allocate64("tags", config.capacity, std::move(kept.tags))
                     : memory.Allocate32("tags", config.capacity, std::move(kept.device_tags32));
  b.sums = wide_sums ? memory.Allocate64("sums", std::size_t(config.capacity) * 3, std::move(kept.device_sums64))
                     : memory.Allocate32("sums", std::size_t(config.capacity) * 3, std::move(kept.device_sums32));
  // packed-decimal's count word is 32-bit (core/shared/packed_sums.h).
  b.counts = packed ? memory.Allocate32("counts", config.capacity)
                    : memory.Allocate64("counts", config.capacity, std::move(kept.counts));
  // Level-major: record i's level k placement at k n + i (core/shared/levels.h).
  b.placements = memory.Allocate32("placements", std::size_t(n) * config.levels, std::move(kept.placements));
  b.wraps = memory.Allocate64("wraps", 2);
  if (config.second_moments) {
    b.keeps_squares = true;
    b.squares =
        wide_sums ? memory.Allocate64("squares", config.capacity) : memory.Allocate32("squares", config.capacity);
    args.square_scale = std::ldexp(1.0, table.square_bits);
  }
  const FrameEffects planned = effects ? *effects : PlanFrameEffects(config, previous ? kLaterFrame : 0);
  // Last-seen frames are tracked whenever eviction is asked for; the pass runs where the plan says.
  const bool tracking = config.eviction.enabled();
  const bool evicting = planned.eviction;
  if (tracking) {
    b.last_seen = memory.Allocate32("last_seen", config.capacity);
    args.track_last_seen = true;
    args.frame = config.frame;
    args.claim_tombstones = config.eviction.by_priority();
  }
  // The double buffer (emulated/temporal_kernel.h): the table before the frame, which the blend reads.
  const bool blending = planned.temporal;  // forced on a first frame, it blends with an empty history
  TemporalArgs temporal{
      config.capacity,
      config.accumulation,
      MakeTemporalParams(config.temporal, config.accumulation, table.fixed_point_bits, table.square_bits),
      b,
      0,
      0};
  if (blending) {
    temporal.previous_sums = wide_sums ? memory.Allocate64("previous_sums", std::size_t(config.capacity) * 3)
                                       : memory.Allocate32("previous_sums", std::size_t(config.capacity) * 3);
    temporal.previous_counts = packed ? memory.Allocate32("previous_counts", config.capacity)
                                      : memory.Allocate64("previous_counts", config.capacity);
    if (config.second_moments) {
      temporal.previous_squares = wide_sums ? memory.Allocate64("previous_squares", config.capacity)
                                            : memory.Allocate32("previous_squares", config.capacity);
    }
    args.temporal = &temporal;
  }
  if (previous) {
    if (previous->capacity != config.capacity || previous->accumulation != config.accumulation) {
      throw ConfigError("--capacity", "the previous frame's table has another shape; start a new sequence");
    }
    if (previous->key_identity != config.key_identity) {
      throw ConfigError("--key-identity", "the previous frame's table stores other identities; start a new sequence");
    }
    if (previous->second_moments != config.second_moments) {
      throw ConfigError("--second-moments", "the previous frame's table keeps other moments; start a new sequence");
    }
    if (config.second_moments &&
        (wide_sums ? previous->fixed_squares.size() : previous->float_squares.size()) != config.capacity) {
      throw InputError("the previous frame's table has no square sum per slot");
    }
    if (config.second_moments && wide_sums) {
      const std::span<std::uint64_t> squares = memory.Words64(b.squares);
      std::copy(previous->fixed_squares.begin(), previous->fixed_squares.end(), squares.begin());
      if (blending) std::copy(squares.begin(), squares.end(), memory.Words64(temporal.previous_squares).begin());
    } else if (config.second_moments) {
      const std::span<std::uint32_t> squares = memory.Words32(b.squares);
      for (std::size_t s = 0; s < config.capacity; ++s)
        squares[s] = std::bit_cast<std::uint32_t>(previous->float_squares[s]);
      if (blending) std::copy(squares.begin(), squares.end(), memory.Words32(temporal.previous_squares).begin());
    }
    if (full_keys) {
      std::copy(previous->tags.begin(), previous->tags.end(), memory.Words64(b.tags).begin());
    } else {
      std::copy(previous->tags.begin(), previous->tags.end(), memory.Words32(b.tags).begin());  // each below 2^32
    }
    if (packed) {
      if (previous->frame_counters.size() != config.capacity) {
        throw InputError("the previous frame's packed-decimal table has no frame counter per slot");
      }
      const std::span<std::uint32_t> words = memory.Words32(b.counts);
      PackCountWords(previous->counts, previous->frame_counters, words);
      if (blending) std::copy(words.begin(), words.end(), memory.Words32(temporal.previous_counts).begin());
    } else {
      std::copy(previous->counts.begin(), previous->counts.end(), memory.Words64(b.counts).begin());
      if (blending)
        std::copy(previous->counts.begin(), previous->counts.end(), memory.Words64(temporal.previous_counts).begin());
    }
    if (tracking)
      std::copy(previous->last_seen.begin(), previous->last_seen.end(), memory.Words32(b.last_seen).begin());
    if (wide_sums) {
      const std::span<std::uint64_t> sums = memory.Words64(b.sums);
      for (std::size_t s = 0; s < config.capacity; ++s) std::copy_n(previous->fixed_sums[s].begin(), 3, &sums[s * 3]);
      if (blending) std::copy(sums.begin(), sums.end(), memory.Words64(temporal.previous_sums).begin());
    } else if (packed) {  // each below 2^32
      const std::span<std::uint32_t> sums = memory.Words32(b.sums);
      for (std::size_t s = 0; s < config.capacity; ++s) {
        for (int c = 0; c < 3; ++c) sums[s * 3 + c] = std::uint32_t(previous->fixed_sums[s][c]);
      }
      if (blending) std::copy(sums.begin(), sums.end(), memory.Words32(temporal.previous_sums).begin());
    } else {
      const std::span<std::uint32_t> sums = memory.Words32(b.sums);
      for (std::size_t s = 0; s < config.capacity; ++s) {
        for (int c = 0; c < 3; ++c) sums[s * 3 + c] = std::bit_cast<std::uint32_t>(previous->float_sums[s][c]);
      }
      if (blending) std::copy(sums.begin(), sums.end(), memory.Words32(temporal.previous_sums).begin());
    }
  }

  // The occupied list (core/compaction.h): the previous frame's, and its flags, where the sequence compacts.
  const bool compacting = config.compaction == Compaction::kOccupiedList;
  CompactionArgs compaction{config.capacity, b, {}};
  OccupiedList& list = compaction.list;
  if (compacting) {
    list = {true,
            memory.Allocate32("listed", config.capacity),
            memory.Allocate32("occupied", config.capacity),
            memory.Allocate64("occupied_count", 1),
            memory.Allocate32("next_occupied", config.capacity),
            memory.Allocate64("next_occupied_count", 1)};
    if (previous) {
      if (!previous->compacted) {
        throw ConfigError("--compaction", "the previous frame's table has no occupied list; start a new sequence");
      }
      const std::span<std::uint32_t> slots = memory.Words32(list.slots);
      const std::span<std::uint32_t> listed = memory.Words32(list.listed);
      std::copy(previous->occupied.begin(), previous->occupied.end(), slots.begin());
      for (const std::uint32_t slot : previous->occupied) {
        if (slot >= config.capacity) {
          throw InputError("the previous frame's occupied list names slot " + std::to_string(slot) + ", past the " +
                           std::to_string(config.capacity) + " slots");
        }
        listed[slot] = 1;
      }
      memory.Words64(list.count)[0] = previous->occupied.size();
    }
    temporal.list = list;
  }
  EvictionArgs eviction{
      config.capacity, config.probe_limit, config.probing, config.frame, config.eviction, b, 0, {}, 0, list, packed};
  if (evicting) {
    eviction.evicted = memory.Allocate64("evicted", 1);
    if (config.eviction.by_priority()) {
      eviction.keys = run.keys;
      eviction.levels = config.levels;
      eviction.normal_in_index = config.normal_in_index;
      eviction.victims = memory.Allocate32("victims", config.capacity);
    }
    args.eviction = &eviction;
  }

  // reads-current-table: each record's scattered vertex keyed as the transport keys it, looked up by the kernel.
  std::vector<KeyResult> scattered_keys;
  TransportInPassArgs transport_args;
  if (transport_in_pass) {
    scattered_keys.resize(n);
    ParallelFor(n, 4096, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const bool transports = !given.scattered.empty() && accepted[i] && shared::RecordHasVertex(all[i]) &&
                                shared::RecordHasVertex(given.scattered[i]) &&
                                CheckRecordInputs(given.scattered[i]) == InputVerdict::kAccepted;
        scattered_keys[i] =
            transports ? shared::ComputeKey(params, given.scattered[i]) : shared::EmptyKeyResult(shared::kKeyNoVertex);
      }
    });
    transport_args = {scattered_keys, given.scattered, table.fixed_point_bits, memory.Allocate32("transport_reads", n)};
    args.transport = &transport_args;
  }
  // The survival-in-pass variant: each record's traced light and draw, for its decision inside the launch.
  SurvivalInPassArgs survival_args;
  std::vector<float> survival_draws;
  const bool survival_in_pass = options.survival_in_pass && config.survival.enabled();
  if (survival_in_pass) {
    const auto traced = options.survival_in_pass->traced.find(given.frame);
    if (traced == options.survival_in_pass->traced.end() || traced->second.size() != given.records.size()) {
      throw InputError("survival in the accumulate: no traced light for each of frame " + std::to_string(given.frame) +
                       "'s " + std::to_string(given.records.size()) + " records");
    }
    survival_draws = SurvivalDraws(given, options.survival_in_pass->seed);
    survival_args = {config.survival, traced->second, survival_draws, table.fixed_point_bits, table.square_bits};
    args.survival = &survival_args;
  }
  const AccumulateKernelFn accumulate_kernel = transport_in_pass  ? TransportDuringAccumulate
                                               : survival_in_pass ? SurvivalDuringAccumulate
                                                                  : accumulate;

  run.timings.clear_ms = clock.LapMs();
  const simt::Kernel kernel = [&](simt::ThreadContext& ctx) { return accumulate_kernel(ctx, args); };
  if (options.mode == simt::Mode::kFast) {
    simt::LaunchFast(memory, n, kernel, options.threads,
                     [&](std::uint32_t i) { PrefetchAccumulate(std::as_const(memory), args, i); });
  } else {
    const std::uint32_t warps = (n + options.warp_size - 1) / options.warp_size;
    std::unique_ptr<simt::Schedule> parsed;
    if (!options.schedule_instance)
      parsed = simt::MakeSchedule(options.schedule, warps,
                                  std::uint64_t(warps) * config.levels * (2 * config.probe_limit + 6));
    simt::Schedule* schedule = options.schedule_instance ? options.schedule_instance : parsed.get();
    simt::OperationObserver observer;
    if (!fixed) {
      run.float_add_order.resize(std::size_t(config.capacity) * 3);
      observer = [&](std::uint32_t thread, const simt::MemoryOp& op) {
        if (op.kind == simt::OpKind::kAtomicAddFloat && op.address.buffer == b.sums)
          run.float_add_order[op.address.index].push_back(thread);
      };
    }
    run.launch = simt::LaunchFaithful(memory, n, options.warp_size, kernel, *schedule, observer,
                                      simt::WeakCasPolicy{options.spurious_cas});
    run.trace_hash = run.launch.trace_hash;
  }

  if (transport_in_pass) {
    const std::span<const std::uint32_t> reads = std::as_const(memory).Words32(transport_args.reads);
    run.transport_read.assign(reads.begin(), reads.end());
    for (std::uint32_t i = 0; i < n; ++i) {
      if (scattered_keys[i].status == shared::kKeyNoVertex) continue;
      ++run.transport.scattered;
      if (scattered_keys[i].status == shared::kKeyUnkeyable) {
        ++run.transport.unkeyable;
      } else if (reads[i] == kNothingTransported) {
        ++run.transport.missed;
      } else {
        ++run.transport.found;
      }
    }
  }
  run.timings.accumulate_ms = clock.LapMs();
  // The passes after the accumulate run one thread per slot. Faithful mode schedules them by the run's policy; an
  // exhaustive search drives only the accumulate launch, so they then take round-robin.
  const auto launch = [&](std::uint32_t threads, const simt::Kernel& kernel,
                          const simt::ThreadPrefetch& prefetch = {}) {
    if (options.mode == simt::Mode::kFast) return simt::LaunchFast(memory, threads, kernel, options.threads, prefetch);
    const std::uint32_t warps = (threads + options.warp_size - 1) / options.warp_size;
    const std::string policy = options.schedule_instance ? "round-robin" : options.schedule;
    const auto schedule = simt::MakeSchedule(policy, warps, std::uint64_t(warps) * (2 * config.probe_limit + 8));
    simt::LaunchFaithful(memory, threads, options.warp_size, kernel, *schedule, {},
                         simt::WeakCasPolicy{options.spurious_cas});
  };
  // With compaction, a pass over slots runs one thread per entry of the list: its count, read back, is the emulator's
  // indirect dispatch. A count past the capacity (a broken kernel's) stands for the whole list.
  const auto list_count = [&] {
    return static_cast<std::uint32_t>(
        std::min<std::uint64_t>(std::as_const(memory).Words64(list.count)[0], config.capacity));
  };
  // An entry's slot is anywhere in the table: its lines are asked for a few entries ahead, as the accumulate's are.
  const auto prefetch_entry = [&](std::uint32_t entry) {
    const std::span<const std::uint32_t> entries = std::as_const(memory).Words32(list.slots);
    if (entry >= entries.size()) return;
    const std::uint32_t slot = entries[entry];
    memory.Prefetch({b.tags, slot});
    memory.Prefetch({b.counts, slot});
    memory.Prefetch({b.sums, std::uint64_t(slot) * 3});
    memory.Prefetch({b.sums, std::uint64_t(slot) * 3 + 2});  // the three sums may straddle two lines
    if (tracking) memory.Prefetch({b.last_seen, slot});
    if (blending) {
      memory.Prefetch({temporal.previous_counts, slot});
      memory.Prefetch({temporal.previous_sums, std::uint64_t(slot) * 3});
      memory.Prefetch({temporal.previous_sums, std::uint64_t(slot) * 3 + 2});
    }
  };
  const auto launch_per_slot = [&](const simt::Kernel& kernel) {
    if (compacting) return launch(list_count(), kernel, prefetch_entry);
    launch(config.capacity, kernel);
  };
  const bool seeding = planned.level_seed;
  HashTableDump empty_table;  // a first frame's table before it, where the seed is forced
  if (seeding && !previous) {
    empty_table.capacity = config.capacity;
    empty_table.probe_limit = config.probe_limit;
    empty_table.probing = config.probing;
    empty_table.fingerprint_bits = config.fingerprint_bits;
    empty_table.key_identity = config.key_identity;
    empty_table.accumulation = config.accumulation;
    empty_table.tags.resize(config.capacity);
    empty_table.counts.resize(config.capacity);
    (fixed ? empty_table.fixed_sums.resize(config.capacity) : empty_table.float_sums.resize(config.capacity));
  }
  if (seeding) {
    LevelSeedArgs seed{run.keys,
                       config.capacity,
                       fixed,
                       config.normal_in_index,
                       config.level_seed,
                       previous ? previous : &empty_table,
                       b,
                       0,
                       0};
    seed.seeded = memory.Allocate32("seeded", config.capacity);
    seed.seeded_count = memory.Allocate64("seeded_count", 1);
    launch(n * config.levels, [&](simt::ThreadContext& ctx) { return LevelSeedKernel(ctx, seed); });
    run.seeded = memory.Words64(seed.seeded_count)[0];
    const std::span<const std::uint32_t> flags = std::as_const(memory).Words32(seed.seeded);
    run.seeded_slots.resize(config.capacity);
    for (std::size_t s = 0; s < config.capacity; ++s) run.seeded_slots[s] = flags[s] == 2;
  }
  // A skipped pass reads zero, not the clock's few nanoseconds between two laps.
  run.timings.level_seed_ms = seeding ? clock.LapMs() : 0.0;
  if (compacting) {
    // Every level's placements (core/shared/levels.h): a coarser cell is listed as any other.
    launch(
        n * config.levels, [&](simt::ThreadContext& ctx) { return GatherOccupiedKernel(ctx, compaction); },
        [&](std::uint32_t i) {
          memory.Prefetch({list.listed, std::as_const(memory).Words32(b.placements)[i]});
        });
  }
  run.timings.compaction_ms = compacting ? clock.LapMs() : 0.0;
  if (blending) launch_per_slot([&](simt::ThreadContext& ctx) { return TemporalKernel(ctx, temporal); });
  run.timings.temporal_ms = blending ? clock.LapMs() : 0.0;
  // The settle after the blend, which reads the frame's adds as differences the halving would break.
  if (packed) {
    const PackedSettleArgs settle{b, memory.Allocate64("halved", 1), list};
    launch_per_slot([&](simt::ThreadContext& ctx) { return PackedSettleKernel(ctx, settle); });
    run.halved = memory.Words64(settle.halved)[0];
  }
  run.timings.settle_ms = packed ? clock.LapMs() : 0.0;
  if (evicting) {
    if (config.eviction.by_priority()) {
      launch(n * config.levels, [&](simt::ThreadContext& ctx) { return eviction_kernels.select(ctx, eviction); });
    }
    launch_per_slot([&](simt::ThreadContext& ctx) { return EvictKernel(ctx, eviction); });
    launch_per_slot([&](simt::ThreadContext& ctx) { return eviction_kernels.reclaim(ctx, eviction); });
    run.evicted = memory.Words64(eviction.evicted)[0];
    if (compacting) {
      launch_per_slot([&](simt::ThreadContext& ctx) { return PruneOccupiedKernel(ctx, compaction); });
      launch(1, [&](simt::ThreadContext& ctx) { return eviction_kernels.finish_prune(ctx, compaction); });
      std::swap(list.slots, list.next_slots);
    }
  }
  if (tracking) table.last_seen = memory.TakeWords32(b.last_seen);
  if (compacting) {
    table.compacted = true;
    // The list as the kernels left it, up to its count, for the checker to hold to the table.
    const std::span<const std::uint32_t> slots = std::as_const(memory).Words32(list.slots);
    table.occupied.assign(slots.begin(), slots.begin() + list_count());
  }
  run.timings.eviction_ms = evicting ? clock.LapMs() : 0.0;
  // The dump: the final state of the device buffers, moved out where the layouts agree.
  if (full_keys) {
    table.tags = memory.TakeWords64(b.tags);
  } else {
    table.tags = ReuseForOverwrite(kept.tags, config.capacity);
    const std::span<const std::uint32_t> tags = std::as_const(memory).Words32(b.tags);
    ParallelFor(config.capacity, 1 << 14, [&](std::size_t begin, std::size_t end) {
      std::copy(tags.begin() + begin, tags.begin() + end, table.tags.begin() + begin);
    });
    kept.device_tags32 = memory.TakeWords32(b.tags);
  }
  if (packed) {
    const std::span<const std::uint32_t> words = std::as_const(memory).Words32(b.counts);
    table.counts.resize(config.capacity);
    table.frame_counters.resize(config.capacity);
    ParallelFor(config.capacity, std::size_t(1) << 16, [&](std::size_t begin, std::size_t end) {
      SplitCountWords(words.subspan(begin, end - begin), std::span(table.counts).subspan(begin, end - begin),
                      std::span(table.frame_counters).subspan(begin, end - begin));
    });
  } else {
    table.counts = memory.TakeWords64(b.counts);
  }
  run.placements = memory.TakeWords32(b.placements);
  run.coarser_placements.assign(run.placements.begin() + n, run.placements.end());
  run.placements.resize(n);
  run.min_count = config.min_count;
  run.neighbour_search = config.neighbour_search;
  run.interpolation = config.interpolation;
  run.own_light = batch.own_light;
  run.key_params = params;
  run.wraps = memory.Words64(b.wraps)[0];
  run.count_wraps = memory.Words64(b.wraps)[1];
  if (fixed) {
    table.fixed_sums = ReuseForOverwrite(kept.fixed_sums, config.capacity);
  } else {
    table.float_sums = ReuseForOverwrite(kept.float_sums, config.capacity);
  }
  const std::span<const std::uint64_t> fixed_words =
      wide_sums ? std::as_const(memory).Words64(b.sums) : std::span<const std::uint64_t>();
  const std::span<const std::uint32_t> narrow_words =
      wide_sums ? std::span<const std::uint32_t>() : std::as_const(memory).Words32(b.sums);
  ParallelFor(config.capacity, 1 << 14, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      for (int c = 0; c < 3; ++c) {
        if (wide_sums) {
          table.fixed_sums[s][c] = fixed_words[std::size_t(s) * 3 + c];
        } else if (packed) {
          table.fixed_sums[s][c] = narrow_words[std::size_t(s) * 3 + c];
        } else {
          table.float_sums[s][c] = std::bit_cast<float>(narrow_words[std::size_t(s) * 3 + c]);
        }
      }
    }
  });
  table.fixed_squares.clear();
  table.float_squares.clear();
  if (config.second_moments && wide_sums) {
    table.fixed_squares = memory.TakeWords64(b.squares);
  } else if (config.second_moments) {
    const std::span<const std::uint32_t> words = std::as_const(memory).Words32(b.squares);
    table.float_squares.resize(config.capacity);
    for (std::size_t s = 0; s < config.capacity; ++s) table.float_squares[s] = std::bit_cast<float>(words[s]);
  }
  if (wide_sums) {
    kept.device_sums64 = memory.TakeWords64(b.sums);
  } else {
    kept.device_sums32 = memory.TakeWords32(b.sums);
  }

  run.timings.read_back_ms = clock.LapMs();
  // Resolve, one pixel per task as on a GPU, each record reading its slot's average; the probe-length
  // histogram and the failures follow from the placements in the same pass. Integer tallies: the totals do not
  // depend on how the pixels are split.
  struct Tally {
    std::uint64_t probe_failures = 0;
    std::vector<std::uint64_t> probe_lengths;
    std::vector<std::uint64_t> resolved_at_level;
    std::uint64_t records_searched = 0;
    std::uint64_t neighbours_read = 0;
  };
  run.image.width = batch.width;
  run.image.height = batch.height;
  run.image.pixels = ReuseForOverwrite(kept.pixels, std::size_t(batch.width) * batch.height);  // every pixel written
  const double unscale = std::ldexp(1.0, -table.fixed_point_bits);  // exact, as FromFixedPoint, without a call per sum
  const std::uint32_t spp = batch.samples_per_pixel;
  // Each record reads its slot at random: the lines of a record a few ahead are asked for while this one is summed,
  // as the accumulate's are (simt::ThreadPrefetch).
  constexpr std::size_t kResolveLookahead = simt::kPrefetchDistance;
  const auto prefetch_slot = [&](std::uint32_t slot) {
    if (slot >= config.capacity) return;
    if (fixed) {
      PrefetchLine(&table.fixed_sums[slot][0]);
      PrefetchLine(&table.fixed_sums[slot][2]);  // 24 bytes may straddle two lines
    } else {
      PrefetchLine(&table.float_sums[slot]);
    }
    PrefetchLine(&table.counts[slot]);
  };
  const shared::ProbeScheme scheme = ProbeSchemeOf(config);
  // A record whose chosen cell holds fewer than min_count samples searches its neighbours (core/neighbour_search.h).
  // A broken resolve (a search that claims writes the table) resolves the pixels on one thread, in order.
  const bool broken_resolve = options.resolve_defect != ResolveDefect::kNone;
  const SlotSearch search = broken_resolve
                                ? BrokenSearch(options.resolve_defect, run)
                                : SlotSearch([&](const Record& r, std::size_t i, const shared::LevelChoice& c) {
                                    return SearchInTable(run, r, i, c);
                                  });
  const Tally tally = ParallelReduce(
      run.image.pixels.size(), broken_resolve ? run.image.pixels.size() + 1 : 2048,
      Tally{0, std::vector<std::uint64_t>(config.probe_limit, 0), std::vector<std::uint64_t>(config.levels, 0)},
      [&](std::size_t begin, std::size_t end, Tally tally) {
        for (std::size_t pixel = begin; pixel < end; ++pixel) {
          glm::dvec3 sum(0.0);
          for (std::uint32_t sample = 0; sample < spp; ++sample) {
            const std::size_t i = pixel * spp + sample;
            if (i + kResolveLookahead < end * spp) prefetch_slot(run.placements[i + kResolveLookahead]);
            const std::uint32_t own = run.placements[i];
            if (own == kProbeFailure) ++tally.probe_failures;
            if (own < config.capacity) {
              const std::uint32_t index = shared::ProbeIndex(scheme, run.keys[i].slot0, own);
              if (index != shared::kNoCandidate) ++tally.probe_lengths[index];
            }
            const shared::LevelChoice chosen =
                broken_resolve ? BrokenLevelChoice(options.resolve_defect, run, i) : ResolvedSlot(run, i);
            const std::uint32_t slot = chosen.slot;
            glm::dvec3 average;
            if (slot < config.capacity && Searches(config.neighbour_search, chosen, config.capacity)) {
              ++tally.resolved_at_level[chosen.level];
              NeighbourReads reads;
              average = *ResolvedAverage(run, batch.records[i], i, chosen, &reads, &search);
              ++tally.records_searched;
              for (const std::uint32_t found : reads.cells) tally.neighbours_read += found != kNotRead;
            } else if (slot < config.capacity) {
              ++tally.resolved_at_level[chosen.level];
              for (int c = 0; c < 3; ++c) {
                const double channel_sum = packed
                                               ? double(table.fixed_sums[slot][c]) / double(shared::kPackedDecimalScale)
                                           : fixed ? double(table.fixed_sums[slot][c]) * unscale
                                                   : double(table.float_sums[slot][c]);
                average[c] = channel_sum / double(table.counts[slot]);
              }
              if (config.interpolation.enabled()) {
                average = Interpolated(config.interpolation, SlotWeight(config.interpolation, table, slot), average,
                                       OwnLight(batch, i));
              }
            }
            if (accepted[i]) sum += AcceptedRecordValue(batch.records[i], slot < config.capacity ? &average : nullptr);
          }
          run.image.pixels[pixel] = PixelMean(sum, spp);
        }
        return tally;
      },
      [](Tally a, const Tally& b) {
        a.probe_failures += b.probe_failures;
        for (std::size_t k = 0; k < a.probe_lengths.size(); ++k) a.probe_lengths[k] += b.probe_lengths[k];
        for (std::size_t k = 0; k < a.resolved_at_level.size(); ++k) a.resolved_at_level[k] += b.resolved_at_level[k];
        a.records_searched += b.records_searched;
        a.neighbours_read += b.neighbours_read;
        return a;
      });
  run.probe_failures = tally.probe_failures;
  if (tracking) {
    for (std::size_t s = 0; s < config.capacity; ++s)
      run.tombstones += table.tags[s] != kEmptyTag && table.counts[s] == 0;
  }
  run.probe_lengths = tally.probe_lengths;
  CountCoarserProbes(run, params);
  run.resolved_at_level = tally.resolved_at_level;
  run.records_searched = tally.records_searched;
  run.neighbours_read = tally.neighbours_read;
  kept.accepted = std::move(accepted);
  kept.entering = std::move(entering);
  run.timings.resolve_ms = clock.LapMs();
  return run;
}

}  // namespace hpsf
