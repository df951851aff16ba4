// A hint to the cache: the line holding an address the caller will read or write soon. Random accesses into the
// table stall a core for a memory latency each; asking for them a few records ahead overlaps the stalls, as a
// GPU overlaps them by running other warps. No result depends on it: a prefetch never faults and changes nothing.
#ifndef HPSF_CORE_PREFETCH_H
#define HPSF_CORE_PREFETCH_H

namespace hpsf {

inline void PrefetchLine(const void* address) {
#if defined(__x86_64__)
  // An instruction, not __builtin_prefetch: GCC 12's dead-code elimination drops builtin prefetches whose address
  // it computes under a condition (a bounds check, a choice of array), which is every useful one here.
  asm volatile("prefetcht0 (%0)" : : "r"(address));
#else
  __builtin_prefetch(address);
#endif
}

}  // namespace hpsf

#endif  // HPSF_CORE_PREFETCH_H
