// Where a HashCache lookup lands (Roth et al. §3.3): the level the pixel's footprint selects and the cell of the
// vertex jittered in its tangent plane. The footprint is hpsf's own (core/footprint.h, Meijer's level of detail): the
// width w = footprint_scale * path length, the level l whose cells (2^(c + l) a side, c the finest's exponent) satisfy
// 2^(c + l) <= w < 2^(c + l + 1), clamped to the octree's levels, read from w's exponent bits. The jitter is the key
// path's (core/shared/jitter.h): p' = p + (s_j 2^(c + l)) ((2 u - 1) T + (2 v - 1) B), Roth's s_c s_j (u t + v b).
#ifndef HPSF_CORE_SHARED_HASHCACHE_LOOKUP_H
#define HPSF_CORE_SHARED_HASHCACHE_LOOKUP_H

#include "cuckoo.h"
#include "hashcache_cell.h"
#include "jitter.h"
#include "level_of_detail.h"
#include "occupancy.h"
#include "record_layout.h"
#include "rng.h"

HPSF_SHARED_BEGIN

struct HashCacheLookupParams {
  OccupancyGrid grid;
  float footprint_scale;  // core/footprint.h's, for the filter width in pixels
  float jitter_scale;     // s_j; 0: no jitter
  uint seed;
  uint frame;
};

HPSF_FN int HashCacheLevelOf(HashCacheLookupParams p, Record r) {
  float d = PathLength(r.position.w, vec3(r.position), vec3(r.previous));
  int c = p.grid.cell_exponent;
  return LevelOfDetail(p.footprint_scale, d, c, c + p.grid.resolution_log2) - c;
}

// The key of the cell a record's vertex looks up at `level`, or kCuckooEmpty where its jittered position is off the
// grid.
HPSF_FN uint HashCacheLookupKey(HashCacheLookupParams p, Record r, int level) {
  RngCounter counter;
  counter.seed = p.seed;
  counter.frame = p.frame;
  counter.pixel = RecordPixel(r);
  counter.sample_index = RecordSample(r);
  counter.bounce = RecordBounce(r);
  uint rng = RngPrefix(counter);
  float u1 = RandomFloatFromPrefix(rng, kJitterDimensionU);
  float u2 = RandomFloatFromPrefix(rng, kJitterDimensionV);
  HPSF_PRECISE float amplitude = Flush(p.jitter_scale * PowerOfTwo(p.grid.cell_exponent + level));
  vec3 jittered = JitterInTangentPlane(vec3(r.position), vec3(r.tangent), vec3(r.bitangent), amplitude, u1, u2);
  ivec3 cell = PointCell(p.grid, jittered);
  if (cell.x < 0) return kCuckooEmpty;
  return CuckooKey(cell.x >> level, cell.y >> level, cell.z >> level, p.grid.resolution_log2 - level);
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_HASHCACHE_LOOKUP_H
