// The large arrays of an emulated run, kept from one run to the next as a GPU backend keeps its device buffers.
// Fresh arrays cost their first touch on every frame: a page fault per page and the kernel zeroing it, some
// 300 MB for a 2-million-record frame, a quarter of the fast backend's time. A run takes its arrays from a
// workspace and a finished run gives them back (Recycle). No contents carry over: the run's host code
// overwrites an array whole, and device buffers are zeroed (simt::DeviceMemory::Allocate32 with storage).
#ifndef HPSF_EMULATED_EMULATOR_WORKSPACE_H
#define HPSF_EMULATED_EMULATOR_WORKSPACE_H

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "core/hash_table.h"
#include "core/hashed_run.h"
#include "core/huge_pages.h"
#include "core/key_batch.h"

namespace hpsf {

struct EmulatorWorkspace {
  // A finished run's arrays come back; the run keeps its scalars and is left with empty arrays.
  void Recycle(HashedRun&& run);

  // Per record.
  std::vector<KeyResult> keys;
  std::vector<std::uint8_t> accepted;
  std::vector<glm::vec3> entering;
  std::vector<std::uint32_t> placements;
  std::vector<glm::vec3> pixels;
  // Per slot: device buffers, and the dump the read-back fills.
  std::vector<SlotTag> tags;                 // the dump's, and the device's with full keys
  std::vector<std::uint32_t> device_tags32;  // the device's with fingerprints
  std::vector<std::uint64_t> counts;
  std::vector<std::uint64_t> device_sums64;  // fixed64
  std::vector<std::uint32_t> device_sums32;  // float32
  std::vector<std::array<std::uint64_t, 3>> fixed_sums;
  std::vector<std::array<float, 3>> float_sums;
};

// A vector of n elements in `spare`'s storage, which it takes, where that is large enough; else fresh storage on
// huge pages. The elements it keeps hold whatever they held: for an array the caller overwrites whole.
template <typename T>
std::vector<T> ReuseForOverwrite(std::vector<T>& spare, std::size_t n) {
  std::vector<T> v = std::exchange(spare, {});
  if (v.capacity() < n) v = {};
  ResizeOnHugePages(v, n);
  return v;
}

}  // namespace hpsf

#endif  // HPSF_EMULATED_EMULATOR_WORKSPACE_H
