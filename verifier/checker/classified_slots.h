// The slots of a hashed table that the contract classifies, over a sequence of frames (docs/design/contract.md: level 3
// and level 4 judge every record outside them): a slot whose placed records carry two or more full keys since it was
// last empty (the fingerprint aliased them, in one frame or across frames), and a slot holding a cell some of whose
// records failed to probe in an earlier frame (the reference kept them; the table never saw them). Within one
// frame a cell's records fail all or none, so for a single frame these are exactly the aliased slots. With priority
// eviction, a cell the table evicted under pressure counts as failed too: the reference, which has no pressure,
// kept it. With level seeds, a cell new in a frame is classified when a neighbour it may be seeded from (parent or
// child, core/level_seed.h) failed, aliased, was evicted under pressure or was itself classified so when new: the
// reference seeds from what it kept;
// and when a neighbour's lookup in the table before the frame aliased (its fingerprint's first slot in the window
// holds another cell, which a hashed backend's seed then reads). With several filtered bounces, a cell fed light that
// a record's transport read from a classified slot, an aliased lookup or a lost cell counts as failed from then on.
#ifndef HPSF_VERIFIER_CHECKER_CLASSIFIED_SLOTS_H
#define HPSF_VERIFIER_CHECKER_CLASSIFIED_SLOTS_H

#include <array>
#include <cstdint>
#include <optional>
#include <set>
#include <vector>

#include "core/hashed_run.h"
#include "core/shared/key_words.h"

namespace hpsf {

class ClassifiedSlots {
 public:
  // normal_in_index: the key's, for the windows a seed's neighbours are looked up in.
  explicit ClassifiedSlots(bool evicts_under_pressure = false, bool seeds_levels = false, bool normal_in_index = true)
      : evicts_under_pressure_(evicts_under_pressure), seeds_levels_(seeds_levels), normal_in_index_(normal_in_index) {}

  // Adds one frame's run, in sequence order, and returns per slot whether it is classified after it. fed: per record
  // (the records then the deeper ones), whether the light it transported was read from where the hashed table could
  // not hold the reference's (verifier/contract/transport_check.h): its cells, at every level, count as failed.
  const std::vector<bool>& AddFrame(const HashedRun& run, const std::vector<bool>& fed = {});

  // This frame's figures: slots aliased, records placed in classified slots (with --levels, each level of a record
  // once), probe failures.
  std::uint64_t aliased_slots() const { return aliased_slots_; }
  std::uint64_t classified_records() const { return classified_records_; }
  // Whether any slot was classified or any record failed, in any frame so far.
  bool any() const { return any_; }

  using FullKey = std::array<std::uint32_t, 6>;
  // After AddFrame: the cell a live slot holds (the full key last placed there), for the lookups that find it.
  const std::optional<FullKey>& KeyOf(std::uint32_t slot) const { return key_of_[slot]; }
  // Whether a cell lost records to a probe failure (or, with pressure, an eviction), or was fed light read from a
  // classified place, in some frame so far.
  bool Lost(const FullKey& key) const { return failed_.contains(key); }
  // Whether a slot was classified after the last frame added (before the next AddFrame: in the table before it).
  bool Classified(std::uint32_t slot) const { return slot < classified_.size() && classified_[slot]; }

 private:
  bool SeedTainted(const FullKey& key) const;
  bool LookupAliased(const shared::KeyWords& neighbour) const;

  bool evicts_under_pressure_, seeds_levels_, normal_in_index_;
  std::optional<HashTableDump> previous_table_;          // with level seeds: the table before this frame
  std::vector<std::optional<FullKey>> previous_key_of_;  // and the live cell of each of its slots
  std::vector<std::optional<FullKey>> key_of_;           // per slot, the full key last placed there since it was empty
  std::vector<std::vector<FullKey>> keys_here_;  // with pressure: per slot, every full key placed since it was empty
  std::vector<bool> aliased_, after_failure_, classified_;
  std::set<FullKey> failed_;   // cells with a probe failure in some frame
  std::set<FullKey> tainted_;  // with level seeds: failed, aliased or evicted under pressure
  std::uint64_t aliased_slots_ = 0, classified_records_ = 0;
  bool any_ = false;
};

}  // namespace hpsf

#endif  // HPSF_VERIFIER_CHECKER_CLASSIFIED_SLOTS_H
