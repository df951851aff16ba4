// Eviction across frames (Binder et al. §3.4, Meijer §4.2): which cells a table forgets after a frame.
// A cell's last-seen frame is the last frame a record was added to it; after a frame's accumulate, a cell last
// seen `unseen_frames` or more frames ago is evicted. strict evicts every cell this frame did not touch
// (unseen_frames 1); stale:N after N frames unseen; none never. A cell this frame touched is never evicted, so
// the frame's resolve reads no evicted cell, before or after the eviction pass.
//
// priority (Binder et al. §3.4.3) evicts under pressure instead of by age: after a frame, in the probe window of
// every record that found no slot, the live cell of lowest priority that the frame did not touch is evicted
// (core/shared/eviction_priority.h orders them: least recently seen, then fewest samples, then the tag's hashed
// bits), so the record finds room next frame. Its tombstones hold the reserved tag kTombstoneTag and an insertion
// may claim them (the others' tombstones keep their cell's tag and are never claimed).
#ifndef HPSF_CORE_EVICTION_H
#define HPSF_CORE_EVICTION_H

#include <cstdint>
#include <string>

namespace hpsf {

enum class EvictionPolicy { kNone, kStrict, kStale, kPriority };

struct Eviction {
  EvictionPolicy policy = EvictionPolicy::kNone;
  std::uint32_t unseen_frames = 0;  // stale:N; 1 for strict; 0 for none and priority

  bool enabled() const { return policy != EvictionPolicy::kNone; }
  // Whether a cell last seen in `last_seen` is evicted by its age after frame `frame` (frames only grow in a
  // sequence); priority evicts by pressure, never by age.
  bool Evicts(std::uint32_t frame, std::uint32_t last_seen) const {
    return enabled() && !by_priority() && frame - last_seen >= unseen_frames;
  }
  bool by_priority() const { return policy == EvictionPolicy::kPriority; }
  std::string ToString() const;  // "none", "strict", "stale:N", "priority"
  bool operator==(const Eviction&) const = default;
};

// Parses "none", "strict", "priority" or "stale:N" with N in [1, 2^20]; a ConfigError naming --eviction otherwise.
Eviction ParseEviction(const std::string& text);

}  // namespace hpsf

#endif  // HPSF_CORE_EVICTION_H
