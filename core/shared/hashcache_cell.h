// A HashCache cell's two sides (Roth et al. §3.1-3.2). A cell keeps light for its front and for its back; its front is
// a compressed normal, claimed by compare-and-swap by the first sample that reaches the cell, and every sample is on
// the front when its normal's dot product with the front's is not negative, else on the back. The decision is exact:
// a front is the top 15 bits of each octahedral coordinate of a record's normal (core/octahedral.h), decoded to an
// integer vector whose dot products are exact in 64 bits, so every backend puts a sample on the same side.
//
// The sort-and-reduce update (core/hashcache_update.h) keys each sample by its cell and side, the segment word
// cell << 1 | back, and carries a coarser level's samples as the finer level's segments: a finer cell's front segment
// stands for its front normal, its back segment for that normal negated (exact: negation maps the lattice onto itself).
#ifndef HPSF_CORE_SHARED_HASHCACHE_CELL_H
#define HPSF_CORE_SHARED_HASHCACHE_CELL_H

#include "cuckoo.h"
#include "occupancy.h"
#include "prelude.h"

HPSF_SHARED_BEGIN

const uint kFrontUnclaimed = 0u;         // no sample has reached the cell
const uint kFrontClaimed = 0x80000000u;  // set in every front, so no front is kFrontUnclaimed
const int kFrontScale = 1 << 17;         // a front's vector has |x| + |y| + |z| = 2^17

// The front word of a record's octahedral normal (u in the low 16 bits, v in the high).
HPSF_FN uint FrontWord(uint octahedral16) {
  return kFrontClaimed | ((octahedral16 & 0xFFFFu) >> 1u) | ((octahedral16 >> 17u) << 15u);
}

// Lattice point q of 15 bits stands for its cell's centre, (2q + 1) 2^-15 - 1, here in units of 2^-17: 8q + 4 - 2^17.
// Every such coordinate is 4 modulo 8 and never 0.
HPSF_FN int FrontCoordinate(uint q) { return int(8u * q + 4u) - kFrontScale; }
HPSF_FN uint FrontLattice(int c) { return uint(c + kFrontScale - 4) >> 3u; }
HPSF_FN int SignOf(int c) { return c < 0 ? -1 : 1; }
HPSF_FN int AbsOf(int c) { return c < 0 ? -c : c; }

// The front's direction as an integer vector, the lower hemisphere unfolded as the octahedral map folds it.
HPSF_FN ivec3 FrontVector(uint front) {
  int u = FrontCoordinate(front & 0x7FFFu);
  int v = FrontCoordinate((front >> 15u) & 0x7FFFu);
  int z = kFrontScale - AbsOf(u) - AbsOf(v);
  if (z >= 0) return ivec3(u, v, z);
  return ivec3((kFrontScale - AbsOf(v)) * SignOf(u), (kFrontScale - AbsOf(u)) * SignOf(v), z);
}

// The front of the opposite direction: decoding it gives FrontVector(front) negated, exactly.
HPSF_FN uint NegatedFront(uint front) {
  ivec3 n = -FrontVector(front);
  int u = n.x;
  int v = n.y;
  if (n.z < 0) {
    u = (kFrontScale - AbsOf(n.y)) * SignOf(n.x);
    v = (kFrontScale - AbsOf(n.x)) * SignOf(n.y);
  }
  return kFrontClaimed | FrontLattice(u) | (FrontLattice(v) << 15u);
}

// Whether a sample standing for `side` lies on the cell's front: their dot product is not negative (products below
// 2^35, sums below 2^37).
HPSF_FN bool FacesFront(uint side, uint front) {
  ivec3 a = FrontVector(side);
  ivec3 b = FrontVector(front);
  int64_t dot = int64_t(a.x) * int64_t(b.x) + int64_t(a.y) * int64_t(b.y) + int64_t(a.z) * int64_t(b.z);
  return dot >= int64_t(0);
}

// A cell and side as one word: the cell's key (below 2^30) shifted, the back's bit below.
HPSF_FN uint SegmentWord(uint key, bool back) { return (key << 1u) | (back ? 1u : 0u); }
HPSF_FN uint SegmentKey(uint segment) { return segment >> 1u; }
HPSF_FN bool SegmentBack(uint segment) { return (segment & 1u) != 0u; }

// The key of a cell's parent: each index halved, packed for the level above (cells_log2 the child level's, >= 1).
HPSF_FN uint ParentKey(uint key, int cells_log2) {
  uint mask = (1u << uint(cells_log2)) - 1u;
  int x = int((key & mask) >> 1u);
  int y = int(((key >> uint(cells_log2)) & mask) >> 1u);
  int z = int((key >> uint(2 * cells_log2)) >> 1u);
  return CuckooKey(x, y, z, cells_log2 - 1);
}

// The finest cell a point lies in: its fixed-point position (FixedVertex, as a triangle's vertex's) shifted down to
// whole cells; (-1, -1, -1) for a point off the grid or too far for fixed point (|x 2^-c| >= 2^30), which is checked
// in float before any conversion.
HPSF_FN ivec3 PointCell(OccupancyGrid g, vec3 p) {
  ivec3 off = ivec3(-1, -1, -1);
  HPSF_PRECISE vec3 scaled = Flush(p) * PowerOfTwo(-g.cell_exponent);
  float limit = PowerOfTwo(30);
  if (!(abs(scaled.x) < limit && abs(scaled.y) < limit && abs(scaled.z) < limit)) return off;
  FixedPoint3 f = FixedVertex(g, p);
  int64_t last = (int64_t(1) << uint(g.resolution_log2)) - int64_t(1);
  int64_t x = f.x >> kOccupancyFractionBits;
  int64_t y = f.y >> kOccupancyFractionBits;
  int64_t z = f.z >> kOccupancyFractionBits;
  if (x < int64_t(0) || y < int64_t(0) || z < int64_t(0) || x > last || y > last || z > last) return off;
  return ivec3(int(x), int(y), int(z));
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_HASHCACHE_CELL_H
