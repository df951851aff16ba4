// The priority eviction of core/eviction.h, shared by C++ and GLSL: the tombstone tag it reserves and the order in
// which it evicts (Binder et al. §3.4.3: a priority from a cell's last access and its number of vertices, ties
// broken by the tag's pseudo-random bits so that evictions spread uniformly over the scene).
#ifndef HPSF_CORE_SHARED_EVICTION_PRIORITY_H
#define HPSF_CORE_SHARED_EVICTION_PRIORITY_H

#include "prelude.h"

HPSF_SHARED_BEGIN

// A priority tombstone's tag: an evicted slot an insertion may claim. No fingerprint equals it, because priority
// eviction needs fingerprints of 31 bits or fewer (core/filter_config.cpp), and no full key, whose high word is
// never 0 (core/shared/full_key.h).
const uint kTombstoneTag = 0xFFFFFFFFu;

// A live slot's priority, lower evicted first: the frame it was last seen in the high word, its count saturated to
// 32 bits in the low word (least recently seen first, then fewest samples).
HPSF_FN uint64_t EvictionPriority(uint last_seen, uint64_t count) {
  const uint64_t saturated = count > uint64_t(0xFFFFFFFFu) ? uint64_t(0xFFFFFFFFu) : count;
  return (uint64_t(last_seen) << 32) | saturated;
}

// Whether slot a (priority, tag) is evicted before slot b; of two equal ones, the first met in the window is. A tag
// is a fingerprint or a full key (core/shared/full_key.h), compared as 64 bits.
HPSF_FN bool EvictedBefore(uint64_t priority_a, uint64_t tag_a, uint64_t priority_b, uint64_t tag_b) {
  return priority_a < priority_b || (priority_a == priority_b && tag_a < tag_b);
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_EVICTION_PRIORITY_H
