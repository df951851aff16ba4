// What every backend returns from filtering one batch (docs/design/README.md): the image, the table as cells,
// where each record went, and the counts a report needs.
#ifndef HPSF_CORE_FILTER_RESULT_H
#define HPSF_CORE_FILTER_RESULT_H

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/neighbour_search.h"
#include "core/transport.h"

namespace hpsf {

inline constexpr std::uint32_t kNoCell = 0xFFFFFFFFu;

// One cell of the table: its key words and what was accumulated into it.
struct TableCell {
  std::array<std::uint32_t, 6> key;
  std::array<std::uint64_t, 3> fixed_sum{};  // fixed64: exact sums with F fraction bits; packed-decimal: at 1000
  std::array<float, 3> float_sum{};          // float32: sums in record order
  // --second-moments (core/shared/second_moment.h): the sum of the records' squared brightness, fixed64 at 2^G
  std::uint64_t fixed_square = 0;
  float float_square = 0.0f;
  std::uint64_t count = 0;
  std::uint32_t last_seen = 0;  // the last frame a record was added to the cell (core/eviction.h)
  std::uint32_t frames = 0;     // packed-decimal: the frames the cell has lived, saturating (core/shared/packed_sums.h)
};

struct FilterStats {
  std::uint64_t records = 0;
  std::uint64_t records_with_vertex = 0;
  std::uint64_t records_without_vertex = 0;  // sky hits and paths that ended before the filter vertex
  std::uint64_t unkeyable = 0;               // fell back to their own contribution
  std::uint64_t rejected_non_finite = 0;     // never entered a table; contribute 0 to their pixel
  std::uint64_t rejected_negative = 0;
  std::uint64_t cells = 0;
  std::uint64_t max_records_per_cell = 0;
  double mean_records_per_cell = 0.0;
  int fixed_point_bits = 0;             // F of fixed64 for this batch
  int square_bits = 0;                  // G of fixed64's square sums, with --second-moments
  std::uint64_t fixed_point_wraps = 0;  // integer adds whose cell sum wrapped (fixed64: a sequence outgrew its F)
  std::uint64_t count_wraps = 0;        // adds whose count wrapped (64-bit, D12; packed-decimal's 24 bits)
  std::uint64_t cells_halved = 0;       // packed-decimal cells the frame's settle halved
  std::uint64_t cells_evicted = 0;      // cells the frame's eviction removed (core/eviction.h)
  std::uint64_t cells_seeded = 0;       // cells new in the frame seeded from another level (core/level_seed.h)
  // [k]: records whose resolve read their cell k levels above their own (--levels, core/shared/levels.h)
  std::vector<std::uint64_t> resolved_at_level;
  // --neighbour-search (core/shared/neighbour_search.h): records whose resolve searched, and the neighbour cells
  // their lookups found
  std::uint64_t records_searched = 0;
  std::uint64_t neighbours_read = 0;
  TransportStats transport;  // several filtered bounces (core/transport.h): the frame's transport, if it ran
};

struct FilterResult {
  Image image;
  std::vector<TableCell> cells;
  std::vector<std::uint32_t> placement;  // per record: index into cells, or kNoCell
  // With --levels L > 1: [(k - 1) n + i], record i's cell k levels above its own, k = 1 .. L - 1
  std::vector<std::uint32_t> coarser_placement;
  // With --neighbour-search: each record that searched, in record order, and the cells (indices into cells) it read
  std::vector<NeighbourReads> neighbour_reads;
  // With a transport (core/transport.h): per record, the cell its scattered vertex's light came from, or
  // kNothingTransported
  std::vector<std::uint32_t> transport_read;
  FilterStats stats;
};

}  // namespace hpsf

#endif  // HPSF_CORE_FILTER_RESULT_H
