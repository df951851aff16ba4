#include "core/compaction.h"

#include "core/error.h"

namespace hpsf {

Compaction ParseCompaction(const std::string& text) {
  if (text == "none") return Compaction::kNone;
  if (text == "occupied-list") return Compaction::kOccupiedList;
  throw ConfigError("--compaction", "expected none or occupied-list; got '" + text + "'");
}

std::string ToString(Compaction compaction) {
  return compaction == Compaction::kOccupiedList ? "occupied-list" : "none";
}

}  // namespace hpsf
