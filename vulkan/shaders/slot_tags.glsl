// A table's tags as its passes read and write them: 32-bit fingerprints, or 64-bit full keys with --key-identity
// full (core/key_identity.h). One buffer, which the includer declares twice at its tags binding, as `tags` (uint)
// and `full_tags` (uint64_t); `full` picks the view, and every tag is handled as a uint64_t (a fingerprint widened).
// An includer whose tags are read-only defines HPSF_TAGS_READONLY.
uint64_t LoadTag(uint slot, bool full) { return full ? full_tags[slot] : uint64_t(tags[slot]); }

#if !defined(HPSF_TAGS_READONLY)
void StoreTag(uint slot, uint64_t tag, bool full) {
  if (full) {
    full_tags[slot] = tag;
  } else {
    tags[slot] = uint(tag);
  }
}

// atomicCompSwap on the tag: what the slot held before.
uint64_t SwapTag(uint slot, uint64_t expected, uint64_t desired, bool full) {
  if (full) return atomicCompSwap(full_tags[slot], expected, desired);
  return uint64_t(atomicCompSwap(tags[slot], uint(expected), uint(desired)));
}
#endif
