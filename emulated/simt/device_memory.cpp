#include "emulated/simt/device_memory.h"

#include <atomic>
#include <bit>
#include <stdexcept>
#include <utility>

#include "core/huge_pages.h"
#include "emulated/simt/kernel_fault.h"

namespace hpsf::simt {

template <typename Word>
void DeviceMemory::ApplyTo(Word& word, MemoryOp& op) {
  const Word old = word;
  op.result = old;
  switch (op.kind) {
    case OpKind::kLoad:
      break;
    case OpKind::kStore:
      word = static_cast<Word>(op.value);
      break;
    case OpKind::kAtomicAdd:
      word = static_cast<Word>(old + static_cast<Word>(op.value));
      break;
    case OpKind::kAtomicAddFloat:
      word = AddFloatBits(old, op.value);
      break;
    case OpKind::kAtomicCas:
      if (old == static_cast<Word>(op.compare)) word = static_cast<Word>(op.value);
      break;
    case OpKind::kAtomicCasWeak:
      if (!op.spurious && old == static_cast<Word>(op.compare)) word = static_cast<Word>(op.value);
      break;
    case OpKind::kAtomicMin:
      if (static_cast<Word>(op.value) < old) word = static_cast<Word>(op.value);
      break;
    case OpKind::kAtomicOr:
      word = old | static_cast<Word>(op.value);
      break;
    case OpKind::kAtomicExchange:
      word = static_cast<Word>(op.value);
      break;
  }
}

const char* ToString(OpKind kind) {
  switch (kind) {
    case OpKind::kLoad:
      return "load";
    case OpKind::kStore:
      return "store";
    case OpKind::kAtomicAdd:
      return "atomic_add";
    case OpKind::kAtomicAddFloat:
      return "atomic_add_float";
    case OpKind::kAtomicCas:
      return "atomic_cas";
    case OpKind::kAtomicMin:
      return "atomic_min";
    case OpKind::kAtomicOr:
      return "atomic_or";
    case OpKind::kAtomicExchange:
      return "atomic_exchange";
    case OpKind::kAtomicCasWeak:
      return "atomic_cas_weak";
  }
  return "?";
}

std::string MemoryOp::ToString() const {
  return std::string(simt::ToString(kind)) + " [" + std::to_string(address.buffer) + "][" +
         std::to_string(address.index) + "] value " + std::to_string(value) + " compare " + std::to_string(compare) +
         " -> " + std::to_string(result);
}

std::uint32_t DeviceMemory::Allocate32(std::string name, std::size_t count, std::vector<std::uint32_t> storage) {
  storage.clear();  // every word value-initialised below: nothing of an earlier run shows through
  buffers_.push_back({std::move(name), false, std::move(storage), {}});
  ResizeOnHugePages(buffers_.back().narrow_words, count);
  UpdateView(static_cast<std::uint32_t>(buffers_.size() - 1));
  return static_cast<std::uint32_t>(buffers_.size() - 1);
}

std::uint32_t DeviceMemory::Allocate64(std::string name, std::size_t count, std::vector<std::uint64_t> storage) {
  storage.clear();
  buffers_.push_back({std::move(name), true, {}, std::move(storage)});
  ResizeOnHugePages(buffers_.back().wide_words, count);
  UpdateView(static_cast<std::uint32_t>(buffers_.size() - 1));
  return static_cast<std::uint32_t>(buffers_.size() - 1);
}

void DeviceMemory::UpdateView(std::uint32_t buffer) {
  if (views_.size() <= buffer) views_.resize(buffer + 1);
  Buffer& b = buffers_[buffer];
  views_[buffer] = b.wide ? View{b.wide_words.data(), b.wide_words.size(), true}
                          : View{b.narrow_words.data(), b.narrow_words.size(), false};
}

std::span<std::uint32_t> DeviceMemory::Words32(std::uint32_t buffer) { return buffers_.at(buffer).narrow_words; }
std::span<std::uint64_t> DeviceMemory::Words64(std::uint32_t buffer) { return buffers_.at(buffer).wide_words; }
std::span<const std::uint32_t> DeviceMemory::Words32(std::uint32_t buffer) const {
  return buffers_.at(buffer).narrow_words;
}
std::span<const std::uint64_t> DeviceMemory::Words64(std::uint32_t buffer) const {
  return buffers_.at(buffer).wide_words;
}

std::vector<std::uint32_t> DeviceMemory::TakeWords32(std::uint32_t buffer) {
  std::vector<std::uint32_t> words = std::move(buffers_.at(buffer).narrow_words);
  UpdateView(buffer);
  return words;
}
std::vector<std::uint64_t> DeviceMemory::TakeWords64(std::uint32_t buffer) {
  std::vector<std::uint64_t> words = std::move(buffers_.at(buffer).wide_words);
  UpdateView(buffer);
  return words;
}

void DeviceMemory::ThrowOutOfBounds(const Address& address) const {
  if (address.buffer >= buffers_.size()) {
    throw KernelFault("access to buffer " + std::to_string(address.buffer) + ", which was never allocated");
  }
  // An out-of-bounds access is a kernel defect (docs/design/defects.md, D8); the emulator reports it instead of
  // corrupting memory.
  throw KernelFault("out-of-bounds access to buffer '" + buffers_[address.buffer].name + "' at index " +
                    std::to_string(address.index) + " of " + std::to_string(views_[address.buffer].size));
}

void DeviceMemory::ApplyConcurrently(MemoryOp& op) {
  switch (op.kind) {
    case OpKind::kLoad:
      return ApplyConcurrently<OpKind::kLoad>(op);
    case OpKind::kStore:
      return ApplyConcurrently<OpKind::kStore>(op);
    case OpKind::kAtomicAdd:
      return ApplyConcurrently<OpKind::kAtomicAdd>(op);
    case OpKind::kAtomicAddFloat:
      return ApplyConcurrently<OpKind::kAtomicAddFloat>(op);
    case OpKind::kAtomicCas:
      return ApplyConcurrently<OpKind::kAtomicCas>(op);
    case OpKind::kAtomicMin:
      return ApplyConcurrently<OpKind::kAtomicMin>(op);
    case OpKind::kAtomicOr:
      return ApplyConcurrently<OpKind::kAtomicOr>(op);
    case OpKind::kAtomicExchange:
      return ApplyConcurrently<OpKind::kAtomicExchange>(op);
    case OpKind::kAtomicCasWeak:
      return ApplyConcurrently<OpKind::kAtomicCasWeak>(op);
  }
}

void DeviceMemory::Apply(MemoryOp& op) {
  const View& view = CheckedView(op.address);
  if (view.wide) {
    ApplyTo(static_cast<std::uint64_t*>(view.words)[op.address.index], op);
  } else {
    ApplyTo(static_cast<std::uint32_t*>(view.words)[op.address.index], op);
  }
}

}  // namespace hpsf::simt
