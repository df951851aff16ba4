// Eviction across frames (issue 14; Binder et al. §3.4, Meijer §4.2): which cells a table forgets after a frame.
// A cell's last-seen frame is the last frame a record was added to it; after a frame's accumulate, a cell last
// seen `unseen_frames` or more frames ago is evicted. strict evicts every cell this frame did not touch
// (unseen_frames 1); stale:N after N frames unseen; none never. A cell this frame touched is never evicted, so
// the frame's resolve reads no evicted cell, before or after the eviction pass.
#ifndef HPSF_CORE_EVICTION_H
#define HPSF_CORE_EVICTION_H

#include <cstdint>
#include <string>

namespace hpsf {

enum class EvictionPolicy { kNone, kStrict, kStale };

struct Eviction {
  EvictionPolicy policy = EvictionPolicy::kNone;
  std::uint32_t unseen_frames = 0;  // stale:N; 1 for strict; 0 for none

  bool enabled() const { return policy != EvictionPolicy::kNone; }
  // Whether a cell last seen in `last_seen` is evicted after frame `frame` (frames only grow in a sequence).
  bool Evicts(std::uint32_t frame, std::uint32_t last_seen) const {
    return enabled() && frame - last_seen >= unseen_frames;
  }
  std::string ToString() const;  // "none", "strict", "stale:N"
  bool operator==(const Eviction&) const = default;
};

// Parses "none", "strict" or "stale:N" with N in [1, 2^20]; a ConfigError naming --eviction otherwise.
Eviction ParseEviction(const std::string& text);

}  // namespace hpsf

#endif  // HPSF_CORE_EVICTION_H
