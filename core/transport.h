// Several filtered bounces on the host (Meijer §4.3, nHPSF; core/shared/transport.h holds the step): before a frame's
// accumulate, each record whose path scattered to a further vertex takes the light the previous frame's table holds
// at that vertex's cell. The frame then adds these transported records to its table as it adds any record, so a
// table of K frames holds up to K + 1 bounces. Only the table before the frame is read, never the one being
// accumulated (D10): on the first frame of a sequence there is none and nothing is transported.
#ifndef HPSF_CORE_TRANSPORT_H
#define HPSF_CORE_TRANSPORT_H

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/accumulation.h"
#include "core/key_batch.h"
#include "core/record.h"
#include "core/temporal.h"

namespace hpsf {

// A cell (or slot) a lookup found with samples: its index and what it held.
struct FoundCell {
  std::uint32_t index = 0;
  CellState state;
};
// Finds the cell of these key words in the table before the frame.
using TransportLookup = std::function<std::optional<FoundCell>(const shared::KeyWords&)>;

inline constexpr std::uint32_t kNothingTransported = 0xFFFFFFFFu;

struct TransportStats {
  std::uint64_t scattered = 0;  // accepted records with a vertex whose scattered vertex is accepted too
  std::uint64_t unkeyable = 0;  // of those, scattered vertices without a key: nothing transported
  std::uint64_t found = 0;      // lookups that found a cell with samples: light transported
  std::uint64_t missed = 0;     // lookups that found none (the cell was never reached, or was evicted)
};

struct TransportResult {
  RecordBatch batch;  // the frame's records and deeper ones, contributions transported; no scattered vertices
  // per record of records then deeper: the cell or slot its transport read, or kNothingTransported
  std::vector<std::uint32_t> read;
  TransportStats stats;
};

// How a scattered vertex is keyed: shared::ComputeKey of it. Tests pass broken variants (emulated/broken_transport.h),
// which see the record it scattered from too.
using ScatteredKeyFn = KeyResult (*)(const KeyParams& params, const Record& scattered, const Record& record);

// A batch's scattered vertices are none, or one per record of records then deeper (without a vertex where its path
// scattered nowhere); an InputError naming the counts otherwise.
void CheckScatteredShape(const RecordBatch& batch);

// Runs body(begin, end) over ranges that cover [0, n), in any order and on any threads; empty: one range on the
// calling thread. Each record's transport is a function of its own inputs and the table before the frame, so the
// result is the same bits however the ranges run (the emulator passes its fast mode's ParallelFor; core itself links
// no thread library).
using RangeLoop = std::function<void(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body)>;

// The records and the deeper ones with their contributions transported from the cells `lookup` finds (which `loop`
// may call from several threads at once). A scattered vertex is keyed like a record (its key path and jitter, from its
// own pixel, sample and bounce) at its own level; the average is the resolve's of one cell (sums / count in double).
TransportResult TransportBatch(const RecordBatch& batch, const KeyParams& params, Accumulation accumulation,
                               int fixed_point_bits, const TransportLookup& lookup, ScatteredKeyFn key = nullptr,
                               const RangeLoop& loop = {});

}  // namespace hpsf

#endif  // HPSF_CORE_TRANSPORT_H
