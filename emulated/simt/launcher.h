// Launching a kernel over N threads on the emulator. Faithful mode: warps of `warp_size` lanes take warp steps
// in the order the schedule picks; a step applies each active lane's pending operation (conflicting ones in
// the schedule's order) and runs those lanes to their next operation. Every faithful run hashes its trace.
// Fast mode: the same kernels run to completion on all cores, operations applied with std::atomic_ref.
#ifndef HPSF_EMULATED_SIMT_LAUNCHER_H
#define HPSF_EMULATED_SIMT_LAUNCHER_H

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "emulated/simt/kernel_task.h"
#include "emulated/simt/schedule.h"

namespace hpsf::simt {

using Kernel = std::function<KernelTask(ThreadContext&)>;

struct LaunchStats {
  std::uint64_t steps = 0;
  std::uint64_t operations = 0;
  std::uint64_t cas_failures = 0;                             // CAS operations whose comparison failed
  std::uint64_t spurious_cas_failures = 0;                    // weak CAS operations the policy failed
  std::uint64_t conflict_groups = 0;                          // same-address groups with a write, summed over steps
  std::map<std::uint32_t, std::uint64_t> active_lanes;        // lanes with an operation in a step -> steps
  std::map<std::uint32_t, std::uint64_t> conflicts_per_step;  // conflict groups in a step -> steps
};

struct LaunchReport {
  std::uint64_t trace_hash = 0;  // faithful mode: a function of (kernel, inputs, warp size, schedule)
  LaunchStats stats;
};

// Sees every operation of a faithful launch as it is applied, in order (a hook, as in Oclgrind's plugins).
using OperationObserver = std::function<void(std::uint32_t thread, const MemoryOp& op)>;

// Which weak compare-and-swaps of a faithful launch fail spuriously: each with `probability`, decided by the counter
// RNG from the launch's step and the lane, so a run replays its failures as it replays its schedule.
struct WeakCasPolicy {
  double probability = 0.0;  // in [0, 1)
  bool Fails(std::uint64_t step, std::uint32_t lane) const;
};

LaunchReport LaunchFaithful(DeviceMemory& memory, std::uint32_t threads, std::uint32_t warp_size, const Kernel& kernel,
                            Schedule& schedule, const OperationObserver& observer = {},
                            const WeakCasPolicy& weak_cas = {});
// Fast mode's stand-in for a GPU's latency hiding: where a GPU runs other warps while one waits on memory, a core
// runs one emulated thread after another, each stalling on its first random access. A prefetch, called for
// thread t + kPrefetchDistance before thread t runs, asks for the lines that thread will touch first (what the
// kernel's arguments say of them, e.g. its key's first slot). It is a hint only: it changes no result.
using ThreadPrefetch = std::function<void(std::uint32_t thread)>;
inline constexpr std::uint32_t kPrefetchDistance = 24;

// worker_threads: 0 for all cores.
void LaunchFast(DeviceMemory& memory, std::uint32_t threads, const Kernel& kernel, int worker_threads = 0,
                const ThreadPrefetch& prefetch = {});

}  // namespace hpsf::simt

#endif  // HPSF_EMULATED_SIMT_LAUNCHER_H
