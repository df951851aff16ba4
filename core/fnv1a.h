// FNV-1a, 64 bits: the checksum of record files and the digest behind cache keys (scenes, converged references).
// Not cryptographic; a consumer that must not mistake one input for another also compares what it hashed.
#ifndef HPSF_CORE_FNV1A_H
#define HPSF_CORE_FNV1A_H

#include <cstddef>
#include <cstdint>

namespace hpsf {

inline constexpr std::uint64_t kFnv1aOffset = 0xcbf29ce484222325ull;

// Continues `hash` over `size` bytes at `data`; start with kFnv1aOffset.
inline std::uint64_t Fnv1a(const void* data, std::size_t size, std::uint64_t hash = kFnv1aOffset) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
  return hash;
}

}  // namespace hpsf

#endif  // HPSF_CORE_FNV1A_H
