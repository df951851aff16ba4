// The emulated backend: the GPU hash table (index hash, fingerprint, bounded linear probing, atomics) run by
// the SIMT emulator, faithfully (warp steps in a scheduled order, traced) or fast (all cores, atomic_ref).
// Keys come from the same core code the reference uses; resolve is core/resolve.
#ifndef HPSF_EMULATED_EMULATED_FILTER_H
#define HPSF_EMULATED_EMULATED_FILTER_H

#include <cstdint>
#include <string>
#include <vector>

#include "core/filter_config.h"
#include "core/hash_table.h"
#include "core/hashed_run.h"
#include "core/image.h"
#include "core/key_batch.h"
#include "core/record.h"
#include "emulated/accumulate_kernel.h"
#include "emulated/broken_resolve.h"
#include "emulated/broken_survival.h"
#include "emulated/broken_transport.h"
#include "emulated/emulator_workspace.h"
#include "emulated/eviction_kernels.h"
#include "emulated/simt/launcher.h"

namespace hpsf {

struct EmulatorOptions {
  simt::Mode mode = simt::Mode::kFast;
  std::uint32_t warp_size = 32;          // 8 (lavapipe), 32 (NVIDIA), 64 (AMD wave64)
  std::string schedule = "round-robin";  // faithful mode: round-robin | random:SEED | pct:SEED:DEPTH
  int threads = 0;                       // fast mode workers; 0: all cores
  // Faithful mode: the share of weak compare-and-swaps that fail spuriously (simt::WeakCasPolicy), in [0, 1). Only
  // kernels that use one see it (hpsf's own claim with a strong one; --inject-defect weak-cas-old-value a weak one).
  double spurious_cas = 0.0;
  // Faithful mode: a schedule object to use instead of parsing `schedule`, kept by the caller across runs;
  // exhaustive search advances one ExhaustiveSchedule from run to run.
  simt::Schedule* schedule_instance = nullptr;
  // The resolve's neighbourhood search broken on purpose (emulated/broken_resolve.h; --inject-defect's resolve
  // variants), as the accumulate kernel is by the kernel argument.
  ResolveDefect resolve_defect = ResolveDefect::kNone;
  // The transport pass broken on purpose (emulated/broken_transport.h), over a sequence of frames.
  TransportDefect transport_defect = TransportDefect::kNone;
  // Path survival decided inside the accumulate's launch (emulated/broken_survival.h), with --survival: the paths as
  // the team traced them, kept by the caller across runs. Null: the records' contributions are added as given.
  const SurvivalInPass* survival_in_pass = nullptr;
  void Validate() const;  // ConfigError naming the option
};

// Wall time of each phase of a run in milliseconds, as VulkanTimings has its passes', for benchmarks and reports;
// no output bit depends on them.
struct EmulatedTimings {
  double transport_ms = 0;    // several filtered bounces' lookups in the table before the frame; 0 without
  double keys_ms = 0;         // keys, input checks and the contributions for F, all cores
  double fixed_point_ms = 0;  // the choice of F
  double clear_ms = 0;        // allocating and zeroing the table
  double accumulate_ms = 0;   // the accumulate launch
  double level_seed_ms = 0;   // the seed launch of resolution changes; 0 without --level-change seed
  double compaction_ms = 0;   // the gather launch of --compaction occupied-list (its prune counts as eviction's)
  double settle_ms = 0;       // packed-decimal's settle launch; 0 for other sums
  double temporal_ms = 0;     // the temporal blend launch; 0 when integrating
  double eviction_ms = 0;     // the evict and reclaim launches; 0 without eviction
  double read_back_ms = 0;    // the dump of the table
  double resolve_ms = 0;      // averages, pixels and the probe statistics, all cores
};

struct EmulatedRun : HashedRun {
  simt::LaunchReport launch;  // faithful mode: trace hash and step statistics
  EmulatedTimings timings;
};

// The accumulate kernel to run; tests pass broken variants of it (docs/design/defects.md).
using AccumulateKernelFn = simt::KernelTask (*)(simt::ThreadContext&, const AccumulateArgs&);

// previous: the table after the frames before this one in a sequence (core/backend.h); the device table starts
// as it, and F is its F. Null: the table starts empty and F is chosen for this batch (and config.frames).
// With a blending config.temporal and a previous table, the temporal launch (emulated/temporal_kernel.h) follows
// the accumulate. With config.eviction, the eviction launches (emulated/eviction_kernels.h) follow, with
// `eviction_kernels` as the selection and reclaim kernels; the run's table is the state after them.
// effects: the passes the frame runs (core/effect_plan.h); null plans them for the first frame or, with `previous`,
// for a later one. workspace: arrays kept from earlier runs (emulated/emulator_workspace.h), which the run takes;
// null: fresh ones. No output bit depends on it.
EmulatedRun EmulatedFilter(const RecordBatch& batch, const FilterConfig& config, const EmulatorOptions& options,
                           AccumulateKernelFn kernel = AccumulateKernel, const HashTableDump* previous = nullptr,
                           EvictionKernels eviction_kernels = {}, const FrameEffects* effects = nullptr,
                           EmulatorWorkspace* workspace = nullptr);

}  // namespace hpsf

#endif  // HPSF_EMULATED_EMULATED_FILTER_H
