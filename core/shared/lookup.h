// A lookup, written once for C++ and GLSL: a probe along a key's candidates (core/shared/probe_scheme.h) for a slot
// that holds its identity, by the passes that read cells other than a record's own (the level seed, the
// neighbourhood search).
#ifndef HPSF_CORE_SHARED_LOOKUP_H
#define HPSF_CORE_SHARED_LOOKUP_H

#include "prelude.h"

HPSF_SHARED_BEGIN

// One candidate of a lookup, a probe for an existing key that never claims: an empty slot ends it (an insertion
// would have taken it, so the key lies in no later slot); a tombstone (an evicted slot, which a live key may have
// probed past, D7), another identity, or the identity without samples is passed.
const uint kLookupEnd = 0u;
const uint kLookupNext = 1u;
const uint kLookupFound = 2u;

HPSF_FN uint LookupStep(uint64_t tag, uint64_t wanted, uint64_t count) {
  if (tag == uint64_t(0u)) return kLookupEnd;
  return tag == wanted && count != uint64_t(0u) ? kLookupFound : kLookupNext;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_LOOKUP_H
