// The probing scheme of a table (core/shared/probe_scheme.h): the order in which a key tries its candidate slots.
// linear:W is hpsf's own; bucket:B and bucket-window:B are NVIDIA SHaRC's with and without compaction
// (docs/design/algorithm.md#probing-schemes). The size (W or B) is FilterConfig::probe_limit.
#ifndef HPSF_CORE_PROBING_H
#define HPSF_CORE_PROBING_H

#include <cstdint>
#include <optional>
#include <string>

#include "core/shared/probe_scheme.h"

namespace hpsf {

enum class ProbeKind { kLinear, kBucket, kBucketWindow };

struct Probing {
  ProbeKind kind = ProbeKind::kLinear;
  std::optional<std::uint32_t> size;  // from "KIND:N"; unset, --probe-limit gives it
};

// Parses "linear", "bucket" or "bucket-window", each optionally with ":N"; a ConfigError naming --probing otherwise.
Probing ParseProbing(const std::string& text);
std::string ToString(ProbeKind kind);  // "linear", "bucket", "bucket-window"
std::uint32_t SharedProbeKind(ProbeKind kind);
shared::ProbeScheme MakeProbeScheme(ProbeKind kind, std::uint32_t capacity, std::uint32_t size);

}  // namespace hpsf

#endif  // HPSF_CORE_PROBING_H
