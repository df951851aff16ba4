#include "emulated/simt/launcher.h"

#include <algorithm>
#include <deque>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/parallel_for.h"
#include "core/shared/rng.h"
#include "emulated/simt/kernel_fault.h"

namespace hpsf::simt {
namespace {

class TraceHash {
 public:
  void Add(std::uint64_t word) {
    for (int byte = 0; byte < 8; ++byte) hash_ = (hash_ ^ ((word >> (8 * byte)) & 0xFFu)) * 0x100000001b3ull;
  }
  std::uint64_t Value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

struct FrameCache {
  void* frame = nullptr;
  std::size_t size = 0;
  ~FrameCache() { ::operator delete(frame); }
};
thread_local FrameCache frame_cache;

}  // namespace

void* KernelTask::promise_type::operator new(std::size_t size) {
  if (frame_cache.frame && frame_cache.size == size) return std::exchange(frame_cache.frame, nullptr);
  return ::operator new(size);
}

void KernelTask::promise_type::operator delete(void* frame, std::size_t size) noexcept {
  if (!frame_cache.frame) {
    frame_cache.frame = frame;
    frame_cache.size = size;
    return;
  }
  ::operator delete(frame);
}

bool WeakCasPolicy::Fails(std::uint64_t step, std::uint32_t lane) const {
  if (probability <= 0.0) return false;
  // A stream of its own (0x3EAC), apart from the schedules' (0x5C4ED).
  const std::uint32_t bits =
      shared::RandomBits(shared::RngCounter{0x3EACu, std::uint32_t(step), std::uint32_t(step >> 32), lane, 0u}, 0u);
  return double(bits) < probability * 4294967296.0;
}
LaunchReport LaunchFaithful(DeviceMemory& memory, std::uint32_t threads, std::uint32_t warp_size, const Kernel& kernel,
                            Schedule& schedule, const OperationObserver& observer, const WeakCasPolicy& weak_cas) {
  if (warp_size == 0) throw std::invalid_argument("warp size must be at least 1");
  std::deque<ThreadContext> contexts;  // stable addresses: kernels keep a reference
  std::vector<KernelTask> tasks;
  tasks.reserve(threads);
  for (std::uint32_t t = 0; t < threads; ++t) {
    contexts.emplace_back(t, memory, Mode::kFaithful);
    tasks.push_back(kernel(contexts.back()));
    tasks.back().Resume();  // to the first memory operation
  }
  const std::uint32_t warps = (threads + warp_size - 1) / warp_size;
  std::vector<std::uint32_t> pending_in_warp(warps, 0);
  for (std::uint32_t t = 0; t < threads; ++t) pending_in_warp[t / warp_size] += contexts[t].Pending() != nullptr;

  LaunchReport report;
  TraceHash trace;
  std::vector<std::uint32_t> ready, lanes, order, group;
  while (true) {
    ready.clear();
    for (std::uint32_t w = 0; w < warps; ++w) {
      if (pending_in_warp[w] > 0) ready.push_back(w);
    }
    if (ready.empty()) break;
    const std::uint32_t warp = ready[schedule.PickWarp(ready)];
    lanes.clear();
    for (std::uint32_t t = warp * warp_size; t < std::min(threads, (warp + 1) * warp_size); ++t) {
      if (contexts[t].Pending()) lanes.push_back(t);
    }
    // Group the step's operations by address, in lane order of first appearance; a group with a write and more
    // than one operation is a conflict the schedule orders.
    order.clear();
    std::vector<bool> placed(lanes.size(), false);
    std::uint32_t conflicts = 0;
    for (std::size_t i = 0; i < lanes.size(); ++i) {
      if (placed[i]) continue;
      group.clear();
      bool writes = false;
      for (std::size_t j = i; j < lanes.size(); ++j) {
        if (!placed[j] && contexts[lanes[j]].Pending()->address == contexts[lanes[i]].Pending()->address) {
          placed[j] = true;
          group.push_back(lanes[j]);
          writes = writes || IsWrite(contexts[lanes[j]].Pending()->kind);
        }
      }
      if (group.size() > 1 && writes) {
        schedule.OrderConflict(group);
        ++conflicts;
      }
      order.insert(order.end(), group.begin(), group.end());
    }
    for (std::uint32_t lane : order) {
      MemoryOp& op = *contexts[lane].Pending();
      if (op.kind == OpKind::kAtomicCasWeak && weak_cas.Fails(report.stats.steps, lane)) {
        op.spurious = true;
        ++report.stats.spurious_cas_failures;
      }
      try {
        memory.Apply(op);
      } catch (const KernelFault& fault) {
        throw KernelFault("thread " + std::to_string(lane) + ": " + fault.what());
      }
      if (observer) observer(lane, op);
      if ((op.kind == OpKind::kAtomicCas || op.kind == OpKind::kAtomicCasWeak) && op.result != op.compare) {
        ++report.stats.cas_failures;
      }
      for (std::uint64_t word : {std::uint64_t(warp), std::uint64_t(lane), std::uint64_t(op.kind),
                                 std::uint64_t(op.address.buffer), op.address.index, op.value, op.compare, op.result}) {
        trace.Add(word);
      }
      if (op.spurious) trace.Add(1);
    }
    for (std::uint32_t lane : lanes) {
      contexts[lane].ClearPending();
      tasks[lane].Resume();
      if (!contexts[lane].Pending()) --pending_in_warp[warp];
    }
    ++report.stats.steps;
    report.stats.operations += lanes.size();
    report.stats.conflict_groups += conflicts;
    ++report.stats.active_lanes[std::uint32_t(lanes.size())];
    ++report.stats.conflicts_per_step[conflicts];
  }
  report.trace_hash = trace.Value();
  return report;
}

void LaunchFast(DeviceMemory& memory, std::uint32_t threads, const Kernel& kernel, int worker_threads,
                const ThreadPrefetch& prefetch) {
  ParallelFor(
      threads, 1024,
      [&](std::size_t begin, std::size_t end) {
        if (prefetch) {
          for (auto t = std::uint32_t(begin); t < std::min<std::size_t>(end, begin + kPrefetchDistance); ++t)
            prefetch(t);
        }
        for (auto t = std::uint32_t(begin); t < end; ++t) {
          if (prefetch && t + kPrefetchDistance < end) prefetch(t + kPrefetchDistance);
          ThreadContext context(t, memory, Mode::kFast);
          KernelTask task = kernel(context);
          try {
            task.Resume();  // never suspends in fast mode: runs to the end
          } catch (const KernelFault& fault) {
            throw KernelFault("thread " + std::to_string(t) + ": " + fault.what());
          }
          if (!task.Done()) throw std::logic_error("a kernel suspended in fast mode");
        }
      },
      worker_threads);
}

}  // namespace hpsf::simt
