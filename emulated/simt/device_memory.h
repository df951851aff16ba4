// Device memory of the emulator: typed buffers of 32- or 64-bit words. Operations are applied one at a time in
// faithful mode (the schedule orders them) or concurrently through std::atomic_ref in fast mode, where plain
// loads and stores are relaxed atomics: racy like a GPU's, without C++ undefined behaviour.
#ifndef HPSF_EMULATED_SIMT_DEVICE_MEMORY_H
#define HPSF_EMULATED_SIMT_DEVICE_MEMORY_H

#include <atomic>
#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/prefetch.h"
#include "emulated/simt/memory_op.h"

namespace hpsf::simt {

class DeviceMemory {
 public:
  // Returns the buffer's id; words start at zero. `storage`: words a caller kept from an earlier run, whose
  // capacity the buffer reuses (all set to zero) instead of touching fresh pages.
  std::uint32_t Allocate32(std::string name, std::size_t count, std::vector<std::uint32_t> storage = {});
  std::uint32_t Allocate64(std::string name, std::size_t count, std::vector<std::uint64_t> storage = {});

  std::span<std::uint32_t> Words32(std::uint32_t buffer);
  std::span<std::uint64_t> Words64(std::uint32_t buffer);
  std::span<const std::uint32_t> Words32(std::uint32_t buffer) const;
  std::span<const std::uint64_t> Words64(std::uint32_t buffer) const;
  // Moves a buffer's words out (read-back without a copy); the buffer is left empty.
  std::vector<std::uint32_t> TakeWords32(std::uint32_t buffer);
  std::vector<std::uint64_t> TakeWords64(std::uint32_t buffer);
  const std::string& Name(std::uint32_t buffer) const { return buffers_.at(buffer).name; }

  // Applies op, fills op.result. Sequential: the caller serialises. An access outside the buffer throws
  // KernelFault.
  void Apply(MemoryOp& op);
  // The same, safe to call from many threads at once.
  void ApplyConcurrently(MemoryOp& op);
  // Asks the cache for the line of a word a thread will access soon (core/prefetch.h); a no-op outside the
  // buffers. A hint: no result depends on it.
  void Prefetch(const Address& address) const {
    if (address.buffer < views_.size() && address.index < views_[address.buffer].size) {
      const View& view = views_[address.buffer];
      PrefetchLine(static_cast<const char*>(view.words) + address.index * (view.wide ? 8 : 4));
    }
  }
  // The same for an operation whose kind is known where it is issued: fast mode's path for every operation of
  // every thread. Inline and without a switch on the kind, so the issuing kernel keeps no indirect jump.
  template <OpKind kKind>
  [[gnu::always_inline]] void ApplyConcurrently(MemoryOp& op) {
    const View& view = CheckedView(op.address);
    if (view.wide) {
      ApplyAtomically<kKind>(static_cast<std::uint64_t*>(view.words)[op.address.index], op);
    } else {
      ApplyAtomically<kKind>(static_cast<std::uint32_t*>(view.words)[op.address.index], op);
    }
  }

 private:
  struct Buffer {
    std::string name;
    bool wide = false;
    std::vector<std::uint32_t> narrow_words;
    std::vector<std::uint64_t> wide_words;
  };
  // Where a buffer's words are, kept beside buffers_ so that an operation finds them with one indexed load.
  struct View {
    void* words = nullptr;
    std::size_t size = 0;
    bool wide = false;
  };
  const View& CheckedView(const Address& address) const {
    if (address.buffer >= views_.size() || address.index >= views_[address.buffer].size) [[unlikely]] {
      ThrowOutOfBounds(address);
    }
    return views_[address.buffer];
  }
  [[noreturn]] void ThrowOutOfBounds(const Address& address) const;
  void UpdateView(std::uint32_t buffer);

  template <typename Word>
  static Word AddFloatBits(Word bits, std::uint64_t operand) {
    const float a = std::bit_cast<float>(static_cast<std::uint32_t>(bits));
    const float sum = a + std::bit_cast<float>(static_cast<std::uint32_t>(operand));
    return static_cast<Word>(std::bit_cast<std::uint32_t>(sum));
  }
  template <typename Word>
  static void ApplyTo(Word& word, MemoryOp& op);
  template <OpKind kKind, typename Word>
  [[gnu::always_inline]] static void ApplyAtomically(Word& word, MemoryOp& op);

  std::vector<Buffer> buffers_;
  std::vector<View> views_;
};

template <OpKind kKind, typename Word>
[[gnu::always_inline]] inline void DeviceMemory::ApplyAtomically(Word& word, MemoryOp& op) {
  std::atomic_ref<Word> ref(word);
  if constexpr (kKind == OpKind::kLoad) {
    op.result = ref.load(std::memory_order_relaxed);
  } else if constexpr (kKind == OpKind::kStore) {
    op.result = 0;
    ref.store(static_cast<Word>(op.value), std::memory_order_relaxed);
  } else if constexpr (kKind == OpKind::kAtomicAdd) {
    op.result = ref.fetch_add(static_cast<Word>(op.value), std::memory_order_relaxed);
  } else if constexpr (kKind == OpKind::kAtomicAddFloat) {
    Word old = ref.load(std::memory_order_relaxed);
    while (!ref.compare_exchange_weak(old, AddFloatBits(old, op.value), std::memory_order_relaxed)) {
    }
    op.result = old;
  } else if constexpr (kKind == OpKind::kAtomicCas || kKind == OpKind::kAtomicCasWeak) {
    Word expected = static_cast<Word>(op.compare);
    ref.compare_exchange_strong(expected, static_cast<Word>(op.value), std::memory_order_relaxed);
    op.result = expected;  // the old value, whether or not the swap happened
  } else if constexpr (kKind == OpKind::kAtomicOr) {
    op.result = ref.fetch_or(static_cast<Word>(op.value), std::memory_order_relaxed);
  } else if constexpr (kKind == OpKind::kAtomicExchange) {
    op.result = ref.exchange(static_cast<Word>(op.value), std::memory_order_relaxed);
  } else {
    static_assert(kKind == OpKind::kAtomicMin);
    Word old = ref.load(std::memory_order_relaxed);
    while (static_cast<Word>(op.value) < old &&
           !ref.compare_exchange_weak(old, static_cast<Word>(op.value), std::memory_order_relaxed)) {
    }
    op.result = old;
  }
}

}  // namespace hpsf::simt

#endif  // HPSF_EMULATED_SIMT_DEVICE_MEMORY_H
