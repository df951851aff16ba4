// Device memory of the emulator: typed buffers of 32- or 64-bit words. Operations are applied one at a time in
// faithful mode (the schedule orders them) or concurrently through std::atomic_ref in fast mode, where plain
// loads and stores are relaxed atomics: racy like a GPU's, without C++ undefined behaviour.
#ifndef HPSF_EMULATED_SIMT_DEVICE_MEMORY_H
#define HPSF_EMULATED_SIMT_DEVICE_MEMORY_H

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "emulated/simt/memory_op.h"

namespace hpsf::simt {

class DeviceMemory {
 public:
  // Returns the buffer's id; words start at zero.
  std::uint32_t Allocate32(std::string name, std::size_t count);
  std::uint32_t Allocate64(std::string name, std::size_t count);

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

 private:
  struct Buffer {
    std::string name;
    bool wide = false;
    std::vector<std::uint32_t> narrow_words;
    std::vector<std::uint64_t> wide_words;
  };
  Buffer& Checked(const Address& address);

  std::vector<Buffer> buffers_;
};

}  // namespace hpsf::simt

#endif  // HPSF_EMULATED_SIMT_DEVICE_MEMORY_H
