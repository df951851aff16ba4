// Kernels are written once as C++20 coroutines, one per emulated thread, that suspend at every global-memory
// operation: `co_await ctx.AtomicAdd(buffer, index, 1)`. In faithful mode the launcher collects each lane's
// pending operation and applies it when the schedule says so; in fast mode the operation is applied at once,
// atomically, and the coroutine does not suspend.
#ifndef HPSF_EMULATED_SIMT_KERNEL_TASK_H
#define HPSF_EMULATED_SIMT_KERNEL_TASK_H

#include <coroutine>
#include <cstdint>
#include <exception>
#include <utility>

#include "emulated/simt/device_memory.h"

namespace hpsf::simt {

class KernelTask {
 public:
  struct promise_type {
    // Fast mode creates one coroutine frame per thread, millions per launch: each worker thread keeps its last
    // freed frame and reuses it, instead of a trip through malloc for every emulated thread.
    static void* operator new(std::size_t size);
    static void operator delete(void* frame, std::size_t size) noexcept;

    KernelTask get_return_object() { return KernelTask(std::coroutine_handle<promise_type>::from_promise(*this)); }
    std::suspend_always initial_suspend() noexcept { return {}; }
    std::suspend_always final_suspend() noexcept { return {}; }
    void return_void() {}
    void unhandled_exception() { exception = std::current_exception(); }
    std::exception_ptr exception;
  };

  KernelTask() = default;
  explicit KernelTask(std::coroutine_handle<promise_type> handle) : handle_(handle) {}
  KernelTask(KernelTask&& other) noexcept : handle_(std::exchange(other.handle_, {})) {}
  KernelTask& operator=(KernelTask&& other) noexcept {
    if (this != &other) {
      Destroy();
      handle_ = std::exchange(other.handle_, {});
    }
    return *this;
  }
  ~KernelTask() { Destroy(); }

  // Runs to the next suspension (faithful) or to the end (fast); rethrows what the kernel threw.
  void Resume() {
    handle_.resume();
    if (handle_.promise().exception) std::rethrow_exception(handle_.promise().exception);
  }
  bool Done() const { return !handle_ || handle_.done(); }

 private:
  void Destroy() {
    if (handle_) handle_.destroy();
    handle_ = {};
  }
  std::coroutine_handle<promise_type> handle_;
};

enum class Mode { kFaithful, kFast };

// What a kernel sees of its thread: its index, and global memory through awaitable operations.
class ThreadContext {
 public:
  ThreadContext(std::uint32_t thread, DeviceMemory& memory, Mode mode)
      : thread_(thread), memory_(&memory), mode_(mode) {}

  std::uint32_t Thread() const { return thread_; }

  // The kind is a template argument so that fast mode's path through DeviceMemory has no switch on it.
  template <OpKind kKind>
  class Operation {
   public:
    Operation(ThreadContext& context, Address address, std::uint64_t value = 0, std::uint64_t compare = 0)
        : context_(context), op_{kKind, address, value, compare} {}
    bool await_ready() {
      if (context_.mode_ != Mode::kFast) return false;
      context_.memory_->ApplyConcurrently<kKind>(op_);
      return true;
    }
    void await_suspend(std::coroutine_handle<>) { context_.pending_ = &op_; }
    std::uint64_t await_resume() const { return op_.result; }
    const MemoryOp& op() const { return op_; }

   private:
    ThreadContext& context_;
    MemoryOp op_;
  };

  Operation<OpKind::kLoad> Load(std::uint32_t buffer, std::uint64_t index) { return {*this, {buffer, index}}; }
  Operation<OpKind::kStore> Store(std::uint32_t buffer, std::uint64_t index, std::uint64_t value) {
    return {*this, {buffer, index}, value};
  }
  Operation<OpKind::kAtomicAdd> AtomicAdd(std::uint32_t buffer, std::uint64_t index, std::uint64_t value) {
    return {*this, {buffer, index}, value};
  }
  Operation<OpKind::kAtomicAddFloat> AtomicAddFloat(std::uint32_t buffer, std::uint64_t index,
                                                    std::uint32_t float_bits) {
    return {*this, {buffer, index}, float_bits};
  }
  Operation<OpKind::kAtomicCas> AtomicCas(std::uint32_t buffer, std::uint64_t index, std::uint64_t compare,
                                          std::uint64_t value) {
    return {*this, {buffer, index}, value, compare};
  }
  Operation<OpKind::kAtomicMin> AtomicMin(std::uint32_t buffer, std::uint64_t index, std::uint64_t value) {
    return {*this, {buffer, index}, value};
  }
  Operation<OpKind::kAtomicOr> AtomicOr(std::uint32_t buffer, std::uint64_t index, std::uint64_t value) {
    return {*this, {buffer, index}, value};
  }
  Operation<OpKind::kAtomicExchange> AtomicExchange(std::uint32_t buffer, std::uint64_t index, std::uint64_t value) {
    return {*this, {buffer, index}, value};
  }

  // A weak compare-and-swap's outcome: the old value, and whether it wrote. A spurious failure reads the word equal
  // to `compare` and still did not write: a kernel that takes the old value alone for its verdict is wrong.
  struct CasResult {
    std::uint64_t old = 0;
    bool exchanged = false;
  };
  class WeakCas {
   public:
    WeakCas(ThreadContext& context, Address address, std::uint64_t compare, std::uint64_t value)
        : operation_(context, address, value, compare) {}
    bool await_ready() { return operation_.await_ready(); }
    void await_suspend(std::coroutine_handle<> handle) { operation_.await_suspend(handle); }
    CasResult await_resume() const {
      const MemoryOp& op = operation_.op();
      return {op.result, op.result == op.compare && !op.spurious};
    }

   private:
    Operation<OpKind::kAtomicCasWeak> operation_;
  };
  WeakCas AtomicCasWeak(std::uint32_t buffer, std::uint64_t index, std::uint64_t compare, std::uint64_t value) {
    return {*this, {buffer, index}, compare, value};
  }

  // Faithful mode: the operation the suspended kernel waits on, or null once it finished. The launcher takes it
  // before it resumes the kernel, so fast mode's operations never write to the context.
  MemoryOp* Pending() const { return pending_; }
  void ClearPending() { pending_ = nullptr; }

 private:
  std::uint32_t thread_;
  DeviceMemory* memory_;
  Mode mode_;
  MemoryOp* pending_ = nullptr;
};

}  // namespace hpsf::simt

#endif  // HPSF_EMULATED_SIMT_KERNEL_TASK_H
