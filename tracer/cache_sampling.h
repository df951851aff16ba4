// How the path tracer feeds the HashCache (Roth et al. §3.2, eq. 1): each path stores its first `store` vertices
// (l_store), each with the light of the `length` vertices after it (l_len): the next-event estimates of itself and the
// next length - 1 vertices and the emission the path finds at the next `length`, weighted by the throughput from it
// (the albedos after it, its own left out, as the cache keeps light without the albedo of the cell it lands in). So a
// path has store + length vertices (l_rec), and every stored vertex accounts for the same number of vertices after it.
#ifndef HPSF_TRACER_CACHE_SAMPLING_H
#define HPSF_TRACER_CACHE_SAMPLING_H

#include <cstdint>

namespace hpsf {

inline constexpr std::uint32_t kMaxCacheStore = 8;  // Roth's largest setting, (8, 8)
inline constexpr std::uint32_t kMaxCacheLength = 8;

struct CacheSampling {
  std::uint32_t store = 3;   // l_store: --cache-store
  std::uint32_t length = 3;  // l_len: --cache-length

  void Validate() const;  // ConfigError naming the option
};

}  // namespace hpsf

#endif  // HPSF_TRACER_CACHE_SAMPLING_H
