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
  ThreadContext(std::uint32_t thread, DeviceMemory& memory, Mode mode) : thread_(thread), memory_(&memory), mode_(mode) {}

  std::uint32_t Thread() const { return thread_; }

  class Operation {
   public:
    Operation(ThreadContext& context, MemoryOp op) : context_(context), op_(op) {}
    bool await_ready() {
      if (context_.mode_ != Mode::kFast) return false;
      context_.memory_->ApplyConcurrently(op_);
      return true;
    }
    void await_suspend(std::coroutine_handle<>) { context_.pending_ = &op_; }
    std::uint64_t await_resume() {
      context_.pending_ = nullptr;
      return op_.result;
    }

   private:
    ThreadContext& context_;
    MemoryOp op_;
  };

  Operation Load(std::uint32_t buffer, std::uint64_t index) { return {*this, {OpKind::kLoad, {buffer, index}}}; }
  Operation Store(std::uint32_t buffer, std::uint64_t index, std::uint64_t value) {
    return {*this, {OpKind::kStore, {buffer, index}, value}};
  }
  Operation AtomicAdd(std::uint32_t buffer, std::uint64_t index, std::uint64_t value) {
    return {*this, {OpKind::kAtomicAdd, {buffer, index}, value}};
  }
  Operation AtomicAddFloat(std::uint32_t buffer, std::uint64_t index, std::uint32_t float_bits) {
    return {*this, {OpKind::kAtomicAddFloat, {buffer, index}, float_bits}};
  }
  Operation AtomicCas(std::uint32_t buffer, std::uint64_t index, std::uint64_t compare, std::uint64_t value) {
    return {*this, {OpKind::kAtomicCas, {buffer, index}, value, compare}};
  }
  Operation AtomicMin(std::uint32_t buffer, std::uint64_t index, std::uint64_t value) {
    return {*this, {OpKind::kAtomicMin, {buffer, index}, value}};
  }

  // Faithful mode: the operation the suspended kernel waits on, or null once it finished.
  MemoryOp* Pending() const { return pending_; }

 private:
  std::uint32_t thread_;
  DeviceMemory* memory_;
  Mode mode_;
  MemoryOp* pending_ = nullptr;
};

}  // namespace hpsf::simt

#endif  // HPSF_EMULATED_SIMT_KERNEL_TASK_H
