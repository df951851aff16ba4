// Resolution changes across frames (Binder et al. §3.4.2): `--level-change none|seed[:S]`. With level of
// detail the level of a location follows the camera, so after a move its records key a cell at another level, which
// starts empty while the old level's cells still hold its estimate. With seed, a cell new in a frame (no samples
// before it) is seeded after the frame's accumulate from the table before the frame: with the sums and counts of
// its 8 children one level finer where any held samples (the resolution decreased: Binder's "simply add up"), else
// with its parent's share one level coarser (the resolution increased: the parent's sums and count shifted right by
// 3 + S, an eighth of it weighted 2^-S, the compromise between less variance and a visible coarse estimate).
// Every backend seeds the same way (core/shared/level_seed.h); the hashed ones find a neighbour by its fingerprint
// in its window of the table before the frame, as a lookup would.
#ifndef HPSF_CORE_LEVEL_SEED_H
#define HPSF_CORE_LEVEL_SEED_H

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/shared/key_words.h"
#include "core/temporal.h"

namespace hpsf {

struct HashTableDump;  // core/hash_table.h, which includes this through core/filter_config.h

struct LevelSeed {
  bool enabled = false;
  std::uint32_t shift = 0;  // S: the parent's share is an eighth times 2^-S

  std::string ToString() const;  // "none", "seed" (S = 0) or "seed:S"
  bool operator==(const LevelSeed&) const = default;
};

// Parses "none", "seed" or "seed:S" with S in [0, 16]; a ConfigError naming --level-change otherwise.
LevelSeed ParseLevelSeed(const std::string& text);

// The seed of the cell with key words `cell`: its children's sums and counts added (in child order, as floats in
// float32) where any child holds samples, else its parent's share, else nothing (count 0). `lookup` gives a
// neighbour's state before the frame, or nothing.
using CellLookup = std::function<std::optional<CellState>(const shared::KeyWords&)>;
CellState SeedOf(const shared::KeyWords& cell, const LevelSeed& seed, bool fixed, const CellLookup& lookup);

// A hashed table's lookup: the first slot of the words' window holding their identity (a fingerprint or a full key)
// with samples, up to the first empty slot. With fingerprints of few bits that slot may hold another cell: the
// lookup aliased.
std::optional<std::uint32_t> FindSlotInTable(const HashTableDump& table, const shared::KeyWords& words,
                                             bool normal_in_index);
// A slot's sums and count.
CellState StateOfSlot(const HashTableDump& table, std::uint32_t slot);
// The state of the slot FindSlotInTable finds.
std::optional<CellState> FindInTable(const HashTableDump& table, const shared::KeyWords& words, bool normal_in_index);

}  // namespace hpsf

#endif  // HPSF_CORE_LEVEL_SEED_H
