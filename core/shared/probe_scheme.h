// How a key's home slot (slot0) orders the slots it may occupy, written once for C++ and GLSL
// (docs/design/algorithm.md#probing-schemes). Every insertion, lookup, eviction and check walks a key's candidates
// through CandidateSlot, so a scheme is one declaration, not a loop per pass:
//   linear:W         slot0, slot0 + 1, ... slot0 + W - 1, wrapping at the capacity (hpsf's own table);
//   bucket:B         the B slots of the bucket aligned to B that holds slot0, from its first slot (SHaRC with
//                    compaction): every key of a bucket has the same candidates in the same order;
//   bucket-window:B  the B slots from min(slot0, capacity - B), never wrapping (SHaRC without compaction).
// Every order runs forwards through consecutive slots, so "the earlier candidates of a key" is one notion for all.
#ifndef HPSF_CORE_SHARED_PROBE_SCHEME_H
#define HPSF_CORE_SHARED_PROBE_SCHEME_H

#include "prelude.h"

HPSF_SHARED_BEGIN

const uint kProbeLinear = 0u;
const uint kProbeBucket = 1u;        // size a power of two
const uint kProbeBucketWindow = 2u;  // size at most the capacity
const uint kNoCandidate = 0xFFFFFFFFu;

struct ProbeScheme {
  uint kind;      // kProbeLinear, kProbeBucket or kProbeBucketWindow
  uint capacity;  // a power of two
  uint size;      // W or B: how many candidates a key has, at most the capacity
};

HPSF_FN ProbeScheme MakeProbeScheme(uint kind, uint capacity, uint size) {
  ProbeScheme s;
  s.kind = kind;
  s.capacity = capacity;
  s.size = size;
  return s;
}

// The first candidate of slot0's order; slot0 < capacity.
HPSF_FN uint FirstCandidate(ProbeScheme s, uint slot0) {
  if (s.kind == kProbeBucket) return slot0 & ~(s.size - 1u);
  if (s.kind == kProbeBucketWindow) return min(slot0, s.capacity - s.size);
  return slot0;
}

// The candidate a key tries at its probe-th step, probe < size.
HPSF_FN uint CandidateSlot(ProbeScheme s, uint slot0, uint probe) {
  if (s.kind == kProbeLinear) return (slot0 + probe) & (s.capacity - 1u);
  return FirstCandidate(s, slot0) + probe;
}

// Where slot lies in slot0's order: its probe index, or kNoCandidate when the key may not occupy it.
HPSF_FN uint ProbeIndex(ProbeScheme s, uint slot0, uint slot) {
  uint index = s.kind == kProbeLinear ? (slot - slot0) & (s.capacity - 1u) : slot - FirstCandidate(s, slot0);
  return index < s.size && slot < s.capacity ? index : kNoCandidate;
}

// The slot `distance` (>= 1) after `slot` in any key's order that holds slot, or kNoCandidate when no order
// continues that far: the slots whose keys may have probed past slot (an eviction's tombstone must stay while one
// of them is live, docs/design/defects.md, D7).
HPSF_FN uint SlotAfter(ProbeScheme s, uint slot, uint distance) {
  if (distance >= s.size) return kNoCandidate;
  if (s.kind == kProbeLinear) return (slot + distance) & (s.capacity - 1u);
  uint offset = s.kind == kProbeBucket ? (slot & (s.size - 1u)) + distance : distance;
  bool inside = s.kind == kProbeBucket ? offset < s.size : slot + distance < s.capacity;
  return inside ? slot + distance : kNoCandidate;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_PROBE_SCHEME_H
