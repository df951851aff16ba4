// Compaction (docs/design/algorithm.md#compaction): `--compaction none|occupied-list`. With occupied-list, a table
// keeps a list of its occupied slots (a tag set: live, or a tombstone) beside a per-slot flag, and the passes that
// step slots (the temporal blend, eviction's evict and reclaim) step the list instead of the whole table: their cost
// follows the occupied slots, not the capacity. The list is kept up to date in proportion to the work: after the
// accumulate a gather pass, one thread per record, lists each placed slot not yet listed; after the reclaim a prune
// pass, one thread per entry, drops the slots it emptied. Bevy's world cache and NVIDIA SHaRC compact their tables
// into such lists; hpsf's list is a function of the table (every occupied slot once, nothing else), checked as an
// invariant of the table (verifier/checker/table_checker.h), and its order is the device's, which no output
// depends on.
#ifndef HPSF_CORE_COMPACTION_H
#define HPSF_CORE_COMPACTION_H

#include <string>

namespace hpsf {

enum class Compaction { kNone, kOccupiedList };

// Parses "none" or "occupied-list"; a ConfigError naming --compaction otherwise.
Compaction ParseCompaction(const std::string& text);
std::string ToString(Compaction compaction);

}  // namespace hpsf

#endif  // HPSF_CORE_COMPACTION_H
