#include "core/probing.h"

#include <charconv>

#include "core/error.h"

namespace hpsf {

Probing ParseProbing(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string name = text.substr(0, colon);
  Probing p;
  if (name == "linear") {
    p.kind = ProbeKind::kLinear;
  } else if (name == "bucket") {
    p.kind = ProbeKind::kBucket;
  } else if (name == "bucket-window") {
    p.kind = ProbeKind::kBucketWindow;
  } else {
    throw ConfigError("--probing", "expected linear, bucket or bucket-window, each optionally :N; got '" + text + "'");
  }
  if (colon == std::string::npos) return p;
  const char* first = text.data() + colon + 1;
  const char* last = text.data() + text.size();
  std::uint32_t size = 0;
  auto [end, error] = std::from_chars(first, last, size);
  if (error != std::errc() || end != last || first == last || size == 0) {
    throw ConfigError("--probing",
                      "the size after ':' must be a positive integer, as in " + name + ":16; got '" + text + "'");
  }
  p.size = size;
  return p;
}

std::string ToString(ProbeKind kind) {
  switch (kind) {
    case ProbeKind::kLinear:
      return "linear";
    case ProbeKind::kBucket:
      return "bucket";
    case ProbeKind::kBucketWindow:
      return "bucket-window";
  }
  return "?";
}

std::uint32_t SharedProbeKind(ProbeKind kind) {
  switch (kind) {
    case ProbeKind::kLinear:
      return shared::kProbeLinear;
    case ProbeKind::kBucket:
      return shared::kProbeBucket;
    case ProbeKind::kBucketWindow:
      return shared::kProbeBucketWindow;
  }
  return shared::kProbeLinear;
}

shared::ProbeScheme MakeProbeScheme(ProbeKind kind, std::uint32_t capacity, std::uint32_t size) {
  return shared::MakeProbeScheme(SharedProbeKind(kind), capacity, size);
}

}  // namespace hpsf
