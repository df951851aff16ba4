// What every hashed backend (emulated, Vulkan) returns from one frame: the image, the table's final state, and
// per record its key and placement, which is all the table checker and the cross-check need to judge it.
#ifndef HPSF_CORE_HASHED_RUN_H
#define HPSF_CORE_HASHED_RUN_H

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "core/cell_interpolation.h"
#include "core/hash_table.h"
#include "core/image.h"
#include "core/key_batch.h"
#include "core/neighbour_search.h"
#include "core/shared/levels.h"
#include "core/transport.h"

namespace hpsf {

struct HashedRun {
  Image image;
  HashTableDump table;
  std::vector<KeyResult> keys;            // per record
  std::vector<std::uint32_t> placements;  // per record: a slot, kProbeFailure or kNotPlaced
  // With --levels L > 1: [(k - 1) n + i], record i's placement k levels above its own cell (core/shared/levels.h)
  std::vector<std::uint32_t> coarser_placements;
  std::vector<std::uint64_t> resolved_at_level;  // [k]: records whose resolve read the slot k levels above their own
  std::uint32_t min_count = 1;                   // the resolve's --min-count
  bool neighbour_search = false;                 // the resolve's --neighbour-search
  CellInterpolation interpolation;               // the resolve's --interpolation (core/cell_interpolation.h)
  std::vector<glm::vec4> own_light;    // the batch's own lights, which the interpolation reads (core/record.h)
  KeyParams key_params{};              // the host's, from which the search's checks compute a record's position again
  std::uint64_t records_searched = 0;  // records whose resolve searched (core/shared/neighbour_search.h)
  std::uint64_t neighbours_read = 0;   // the neighbour slots their lookups found
  // Several filtered bounces (core/transport.h): per record, the slot of the table before the frame its scattered
  // vertex's light came from, or kNothingTransported (empty where the frame transported nothing), and the counts
  std::vector<std::uint32_t> transport_read;
  TransportStats transport;
  std::uint64_t probe_failures = 0;
  std::uint64_t wraps = 0;                   // integer adds whose sum wrapped (64 bits, or packed-decimal's 32)
  std::uint64_t count_wraps = 0;             // adds whose count wrapped (64 bits, D12, or packed-decimal's 24)
  std::vector<std::uint64_t> probe_lengths;  // [k]: records placed after probing k + 1 slots
  std::uint64_t evicted = 0;                 // live slots this frame's eviction made tombstones
  std::uint64_t tombstones = 0;              // tombstones left after the frame (core/hash_table.h)
  std::uint64_t seeded = 0;                  // new slots seeded from another level (core/level_seed.h)
  std::uint64_t halved = 0;                  // packed-decimal slots the settle halved (core/shared/packed_sums.h)
  // Where the backend chooses the interleaving (the faithful emulator): a hash of the schedule's trace, equal on
  // two runs of one seed; 0 elsewhere. And in float32 there, for slot s and channel c, [3 s + c] lists the
  // records in the order their adds applied, and with --level-change seed the slots a seed was added to (after
  // the adds); both empty elsewhere.
  std::uint64_t trace_hash = 0;
  std::vector<std::vector<std::uint32_t>> float_add_order;
  std::vector<bool> seeded_slots;
};

// Record i's placement k levels above its own cell (k = 0: its own); kNotPlaced past what the backend wrote.
std::uint32_t LevelPlacement(const HashedRun& run, std::size_t i, std::uint32_t k);

// The slot record i's resolve reads (core/shared/levels.h): its finest placed level whose count reaches min_count,
// else its coarsest placed one; slot >= capacity where none is placed.
shared::LevelChoice ResolvedSlot(const HashedRun& run, std::size_t i);

// Fills run.resolved_at_level from ResolvedSlot of every record placed at some level.
void CountResolvedLevels(HashedRun& run);

// A record's search in a hashed table: the stencil's slots around its chosen level.
using SlotSearch = std::function<NeighbourReads(const Record& r, std::size_t i, const shared::LevelChoice& chosen)>;

// The search a correct resolve runs: SearchNeighbours with the record's key computed again, each corner looked up in
// the table as read back (core/level_seed.h's FindSlotInTable). words, when given, receives the corners' key words.
NeighbourReads SearchInTable(const HashedRun& run, const Record& r, std::size_t i, const shared::LevelChoice& chosen,
                             std::array<shared::KeyWords, shared::kStencilCells - 1>* words = nullptr);

// What record i's resolve reads in the run's table and averages: the slot of its chosen level (ResolvedSlot's, or a
// broken resolve's) and, where it searches (core/neighbour_search.h), the slots `search` found (by default
// SearchInTable). Nothing where no level is placed. reads, when given, receives the search's. With --interpolation,
// what the record's vertex receives: that average blended with its own light by the slot's weight.
std::optional<glm::dvec3> ResolvedAverage(const HashedRun& run, const Record& r, std::size_t i,
                                          const shared::LevelChoice& chosen, NeighbourReads* reads = nullptr,
                                          const SlotSearch* search = nullptr);

// Fills run.records_searched and run.neighbours_read from SearchInTable of every record that searches.
void CountSearches(HashedRun& run, const RecordBatch& batch);

// Per slot: whether its placed records carry two or more different full keys (the fingerprint aliased them).
std::vector<bool> AliasedSlots(const HashedRun& run);

// Adds the coarser levels' probe failures and lengths (core/shared/levels.h) to the run's, from their placements and
// the slot0 of their keys (derived from each record's own by `params`).
void CountCoarserProbes(HashedRun& run, const KeyParams& params);

// Probe failures and the probe-length histogram, from the placements and slot0 of each record, every level's.
void CountProbes(HashedRun& run);

}  // namespace hpsf

#endif  // HPSF_CORE_HASHED_RUN_H
