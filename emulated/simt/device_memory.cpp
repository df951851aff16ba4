#include "emulated/simt/device_memory.h"

#include <atomic>
#include <bit>
#include <stdexcept>
#include <utility>

#include "core/huge_pages.h"
#include "emulated/simt/kernel_fault.h"

namespace hpsf::simt {
namespace {

template <typename Word>
Word AddFloatBits(Word bits, std::uint64_t operand) {
  const float sum = std::bit_cast<float>(static_cast<std::uint32_t>(bits)) + std::bit_cast<float>(static_cast<std::uint32_t>(operand));
  return static_cast<Word>(std::bit_cast<std::uint32_t>(sum));
}

template <typename Word>
void ApplyTo(Word& word, MemoryOp& op) {
  const Word old = word;
  op.result = old;
  switch (op.kind) {
    case OpKind::kLoad: break;
    case OpKind::kStore: word = static_cast<Word>(op.value); break;
    case OpKind::kAtomicAdd: word = static_cast<Word>(old + static_cast<Word>(op.value)); break;
    case OpKind::kAtomicAddFloat: word = AddFloatBits(old, op.value); break;
    case OpKind::kAtomicCas: if (old == static_cast<Word>(op.compare)) word = static_cast<Word>(op.value); break;
    case OpKind::kAtomicMin: if (static_cast<Word>(op.value) < old) word = static_cast<Word>(op.value); break;
  }
}

template <typename Word>
void ApplyAtomically(Word& word, MemoryOp& op) {
  std::atomic_ref<Word> ref(word);
  switch (op.kind) {
    case OpKind::kLoad: op.result = ref.load(std::memory_order_relaxed); break;
    case OpKind::kStore:
      op.result = 0;
      ref.store(static_cast<Word>(op.value), std::memory_order_relaxed);
      break;
    case OpKind::kAtomicAdd: op.result = ref.fetch_add(static_cast<Word>(op.value), std::memory_order_relaxed); break;
    case OpKind::kAtomicAddFloat: {
      Word old = ref.load(std::memory_order_relaxed);
      while (!ref.compare_exchange_weak(old, AddFloatBits(old, op.value), std::memory_order_relaxed)) {
      }
      op.result = old;
      break;
    }
    case OpKind::kAtomicCas: {
      Word expected = static_cast<Word>(op.compare);
      ref.compare_exchange_strong(expected, static_cast<Word>(op.value), std::memory_order_relaxed);
      op.result = expected;  // the old value, whether or not the swap happened
      break;
    }
    case OpKind::kAtomicMin: {
      Word old = ref.load(std::memory_order_relaxed);
      while (static_cast<Word>(op.value) < old && !ref.compare_exchange_weak(old, static_cast<Word>(op.value), std::memory_order_relaxed)) {
      }
      op.result = old;
      break;
    }
  }
}

}  // namespace

const char* ToString(OpKind kind) {
  switch (kind) {
    case OpKind::kLoad: return "load";
    case OpKind::kStore: return "store";
    case OpKind::kAtomicAdd: return "atomic_add";
    case OpKind::kAtomicAddFloat: return "atomic_add_float";
    case OpKind::kAtomicCas: return "atomic_cas";
    case OpKind::kAtomicMin: return "atomic_min";
  }
  return "?";
}

std::string MemoryOp::ToString() const {
  return std::string(simt::ToString(kind)) + " [" + std::to_string(address.buffer) + "][" + std::to_string(address.index) +
         "] value " + std::to_string(value) + " compare " + std::to_string(compare) + " -> " + std::to_string(result);
}

std::uint32_t DeviceMemory::Allocate32(std::string name, std::size_t count) {
  buffers_.push_back({std::move(name), false, {}, {}});
  ResizeOnHugePages(buffers_.back().narrow_words, count);
  return static_cast<std::uint32_t>(buffers_.size() - 1);
}

std::uint32_t DeviceMemory::Allocate64(std::string name, std::size_t count) {
  buffers_.push_back({std::move(name), true, {}, {}});
  ResizeOnHugePages(buffers_.back().wide_words, count);
  return static_cast<std::uint32_t>(buffers_.size() - 1);
}

std::span<std::uint32_t> DeviceMemory::Words32(std::uint32_t buffer) { return buffers_.at(buffer).narrow_words; }
std::span<std::uint64_t> DeviceMemory::Words64(std::uint32_t buffer) { return buffers_.at(buffer).wide_words; }
std::span<const std::uint32_t> DeviceMemory::Words32(std::uint32_t buffer) const { return buffers_.at(buffer).narrow_words; }
std::span<const std::uint64_t> DeviceMemory::Words64(std::uint32_t buffer) const { return buffers_.at(buffer).wide_words; }

std::vector<std::uint32_t> DeviceMemory::TakeWords32(std::uint32_t buffer) { return std::move(buffers_.at(buffer).narrow_words); }
std::vector<std::uint64_t> DeviceMemory::TakeWords64(std::uint32_t buffer) { return std::move(buffers_.at(buffer).wide_words); }

DeviceMemory::Buffer& DeviceMemory::Checked(const Address& address) {
  Buffer& b = buffers_.at(address.buffer);
  const std::size_t size = b.wide ? b.wide_words.size() : b.narrow_words.size();
  // An out-of-bounds access is a kernel defect (DESIGN.md D8); the emulator reports it instead of corrupting memory.
  if (address.index >= size) {
    throw KernelFault("out-of-bounds access to buffer '" + b.name + "' at index " + std::to_string(address.index) +
                            " of " + std::to_string(size));
  }
  return b;
}

void DeviceMemory::Apply(MemoryOp& op) {
  Buffer& b = Checked(op.address);
  if (b.wide) {
    ApplyTo(b.wide_words[op.address.index], op);
  } else {
    ApplyTo(b.narrow_words[op.address.index], op);
  }
}

void DeviceMemory::ApplyConcurrently(MemoryOp& op) {
  Buffer& b = Checked(op.address);
  if (b.wide) {
    ApplyAtomically(b.wide_words[op.address.index], op);
  } else {
    ApplyAtomically(b.narrow_words[op.address.index], op);
  }
}

}  // namespace hpsf::simt
