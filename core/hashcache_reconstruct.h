// Reconstruction from the HashCache (Roth et al. §3.3), the reference's: each camera sample's primary vertex (a record
// of a frame traced to its primary hits) looks up the level its footprint selects, at its position jittered in its
// tangent plane (core/shared/hashcache_lookup.h), and reads the side of the cell its normal lies on: the side's
// average (its sum over its count) is the light arriving there without albedo, which the record's throughput (the
// albedo) brings to the pixel, after the emission the camera saw (the record's radiance_before). A lookup finds no
// light where the jittered position is off the grid, in a cell the map does not hold (no geometry there: Roth's
// invalid cell), or on a side no sample reached; as Roth fills them, such a sample takes the average light of the
// valid samples of the pixels around its own (its 3 x 3 neighbourhood, its own pixel included), and the fraction of
// samples so filled is reported. A sample with no neighbour to take from stays dark and is counted too.
#ifndef HPSF_CORE_HASHCACHE_RECONSTRUCT_H
#define HPSF_CORE_HASHCACHE_RECONSTRUCT_H

#include <cstdint>
#include <vector>

#include "core/hashcache.h"
#include "core/image.h"
#include "core/record.h"
#include "core/shared/hashcache_lookup.h"

namespace hpsf {

struct HashCacheReconstruction {
  Image image;
  std::uint64_t lookups = 0;             // samples with a primary vertex
  std::uint64_t off_grid = 0;            // jittered off the grid
  std::uint64_t invalid = 0;             // in a cell the map does not hold
  std::uint64_t unsampled = 0;           // on a side no sample reached
  std::uint64_t filled = 0;              // of those three, filled from the pixels around
  std::uint64_t unfilled = 0;            // left dark: no pixel around had a valid sample
  std::vector<std::uint64_t> per_level;  // lookups per level, the finest first
  double FilledFraction() const { return lookups == 0 ? 0.0 : double(filled) / double(lookups); }
};

// The image of `primary` (one record per camera sample, RecordBatch order) reconstructed from `cache`.
HashCacheReconstruction ReconstructHashCache(const HashCache& cache, const RecordBatch& primary,
                                             const shared::HashCacheLookupParams& params);

}  // namespace hpsf

#endif  // HPSF_CORE_HASHCACHE_RECONSTRUCT_H
