#include "core/eviction.h"

#include <charconv>

#include "core/error.h"

namespace hpsf {

std::string Eviction::ToString() const {
  switch (policy) {
    case EvictionPolicy::kNone:
      return "none";
    case EvictionPolicy::kStrict:
      return "strict";
    case EvictionPolicy::kStale:
      return "stale:" + std::to_string(unseen_frames);
    case EvictionPolicy::kPriority:
      return "priority";
  }
  return "?";
}

Eviction ParseEviction(const std::string& text) {
  if (text == "none") return {EvictionPolicy::kNone, 0};
  if (text == "strict") return {EvictionPolicy::kStrict, 1};
  if (text == "priority") return {EvictionPolicy::kPriority, 0};
  const std::string prefix = "stale:";
  if (text.rfind(prefix, 0) == 0) {
    const char* first = text.data() + prefix.size();
    const char* last = text.data() + text.size();
    std::uint32_t frames = 0;
    auto [end, error] = std::from_chars(first, last, frames);
    if (error == std::errc() && end == last && first != last && frames >= 1 && frames <= (1u << 20)) {
      return {EvictionPolicy::kStale, frames};
    }
    throw ConfigError("--eviction", "stale needs a number of frames in [1, 2^20], as in stale:4; got '" + text + "'");
  }
  throw ConfigError("--eviction", "expected none, strict, stale:N or priority; got '" + text + "'");
}

}  // namespace hpsf
