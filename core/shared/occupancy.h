// The occupancy of Roth et al.'s HashCache (§3.1): the cells of an octree's grid that the scene's triangles meet, as
// bits of a field of 32-bit words, each word a block of 4 x 4 x 2 cells. Every later lookup of the cache depends on
// it, so it is exact: a triangle's vertices are rounded to fixed point at 2^-kOccupancyFractionBits of a finest cell
// (correctly rounded, half to even), and a cell is occupied when its closed box meets that triangle, decided by the
// separating-axis test (Akenine-Moller's 13 axes) in 64-bit integers, with no rounding at all. A triangle that only
// grazes a cell (touches a face, an edge or a corner of its box) occupies it; a degenerate one (a segment or a point)
// occupies the cells it meets.
//
// The grid: the finest cell's side is 2^cell_exponent world units; a finest cell's index relative to the grid is
// floor(x * 2^-cell_exponent) - origin (exact: a power-of-two scale and an integer difference); 2^resolution_log2
// finest cells per axis. A cell of level l (0 the finest) is 2^l finest cells a side, its index the finest one's
// shifted right by l, so every level is aligned with the finest.
#ifndef HPSF_CORE_SHARED_OCCUPANCY_H
#define HPSF_CORE_SHARED_OCCUPANCY_H

#include "float_bits.h"
#include "prelude.h"

HPSF_SHARED_BEGIN

const int kOccupancyFractionBits = 8;  // F: a vertex is rounded to 2^-8 of a finest cell
// At most 2^10 finest cells per axis: with F = 8 every product of the test stays below 2^62 (3 (L + F) + 5 bits for
// the triangle normal's axis).
const int kMaxOccupancyResolutionLog2 = 10;
const int kMinOccupancyResolutionLog2 = 2;  // a 4 x 4 x 2 block needs 4 cells per axis

struct OccupancyGrid {
  int cell_exponent;  // the finest cell's side is 2^cell_exponent
  int origin_x;       // the grid's first finest cell, in finest cells of the world's lattice
  int origin_y;
  int origin_z;
  int resolution_log2;  // L: 2^L finest cells per axis
};

// A point in fixed point relative to the grid's origin: 2^F units to a finest cell.
struct FixedPoint3 {
  int64_t x;
  int64_t y;
  int64_t z;
};

// x * 2^(F - cell_exponent) rounded half to even, as an integer: exact, since the power-of-two scale is exact in float
// (a denormal input is flushed to zero first; one whose product would be denormal rounds to 0 either way) and
// rounding a float to an integer is. |x * 2^-cell_exponent| must stay below 2^31 (the host checks its scene's).
HPSF_FN int64_t FixedCoordinate(float x, int cell_exponent) {
  HPSF_PRECISE float scaled = Flush(x) * PowerOfTwo(kOccupancyFractionBits - cell_exponent);
  return int64_t(HPSF_ROUND_EVEN(scaled));
}

HPSF_FN FixedPoint3 FixedVertex(OccupancyGrid g, vec3 v) {
  FixedPoint3 p;
  p.x = FixedCoordinate(v.x, g.cell_exponent) - (int64_t(g.origin_x) << kOccupancyFractionBits);
  p.y = FixedCoordinate(v.y, g.cell_exponent) - (int64_t(g.origin_y) << kOccupancyFractionBits);
  p.z = FixedCoordinate(v.z, g.cell_exponent) - (int64_t(g.origin_z) << kOccupancyFractionBits);
  return p;
}

HPSF_FN FixedPoint3 FixedSub(FixedPoint3 a, FixedPoint3 b) {
  FixedPoint3 d;
  d.x = a.x - b.x;
  d.y = a.y - b.y;
  d.z = a.z - b.z;
  return d;
}

HPSF_FN int64_t FixedAbs(int64_t a) { return a < int64_t(0) ? -a : a; }
HPSF_FN int64_t FixedMin3(int64_t a, int64_t b, int64_t c) { return min(a, min(b, c)); }
HPSF_FN int64_t FixedMax3(int64_t a, int64_t b, int64_t c) { return max(a, max(b, c)); }

// Whether the projections p0, p1, p2 of a triangle onto an axis miss the box's projection [-r, r]: a separating axis.
// A projection that touches it (equals r or -r) does not separate: boxes are closed.
HPSF_FN bool Separates(int64_t p0, int64_t p1, int64_t p2, int64_t r) {
  return FixedMin3(p0, p1, p2) > r || FixedMax3(p0, p1, p2) < -r;
}

// The separating axis e x u for the triangle edge e and the box axis u (0: x, 1: y, 2: z), with the vertices a, b, c
// relative to the box's centre and h its half side.
HPSF_FN bool EdgeAxisSeparates(FixedPoint3 e, int u, FixedPoint3 a, FixedPoint3 b, FixedPoint3 c, int64_t h) {
  // e x x = (0, e.z, -e.y), e x y = (-e.z, 0, e.x), e x z = (e.y, -e.x, 0)
  int64_t ax = u == 0 ? int64_t(0) : (u == 1 ? -e.z : e.y);
  int64_t ay = u == 0 ? e.z : (u == 1 ? int64_t(0) : -e.x);
  int64_t az = u == 0 ? -e.y : (u == 1 ? e.x : int64_t(0));
  int64_t r = h * (FixedAbs(ax) + FixedAbs(ay) + FixedAbs(az));
  return Separates(ax * a.x + ay * a.y + az * a.z, ax * b.x + ay * b.y + az * b.z, ax * c.x + ay * c.y + az * c.z, r);
}

// Whether the closed box of the cell (cx, cy, cz) of `level` meets the closed triangle v0 v1 v2 (fixed-point vertices
// of FixedVertex, inside the grid).
HPSF_FN bool TriangleMeetsCell(FixedPoint3 v0, FixedPoint3 v1, FixedPoint3 v2, int cx, int cy, int cz, int level) {
  int shift = kOccupancyFractionBits + level;
  int64_t h = int64_t(1) << (shift - 1);  // half a side
  FixedPoint3 centre;
  centre.x = (int64_t(cx) << shift) + h;
  centre.y = (int64_t(cy) << shift) + h;
  centre.z = (int64_t(cz) << shift) + h;
  FixedPoint3 a = FixedSub(v0, centre);
  FixedPoint3 b = FixedSub(v1, centre);
  FixedPoint3 c = FixedSub(v2, centre);
  // The box's three axes.
  if (Separates(a.x, b.x, c.x, h) || Separates(a.y, b.y, c.y, h) || Separates(a.z, b.z, c.z, h)) return false;
  FixedPoint3 e0 = FixedSub(b, a);
  FixedPoint3 e1 = FixedSub(c, b);
  FixedPoint3 e2 = FixedSub(a, c);
  // The triangle's normal (zero for a degenerate triangle, which then never separates: the edge axes decide).
  FixedPoint3 n;
  n.x = e0.y * e1.z - e0.z * e1.y;
  n.y = e0.z * e1.x - e0.x * e1.z;
  n.z = e0.x * e1.y - e0.y * e1.x;
  int64_t distance = n.x * a.x + n.y * a.y + n.z * a.z;
  int64_t reach = h * (FixedAbs(n.x) + FixedAbs(n.y) + FixedAbs(n.z));
  if (distance > reach || distance < -reach) return false;
  // The nine products of an edge and a box axis.
  for (int u = 0; u < 3; ++u) {
    if (EdgeAxisSeparates(e0, u, a, b, c, h) || EdgeAxisSeparates(e1, u, a, b, c, h) ||
        EdgeAxisSeparates(e2, u, a, b, c, h)) {
      return false;
    }
  }
  return true;
}

// The cells of `level` whose closed boxes meet the triangle's bounding box (i 2^s <= max and (i + 1) 2^s >= min, s the
// level's side in fixed units), clamped to the grid: the cells a triangle tests.
struct CellRange {
  int x0;
  int y0;
  int z0;
  int x1;  // inclusive
  int y1;
  int z1;
};

HPSF_FN int FirstCellOf(int64_t low, int shift, int64_t last) {
  return int(clamp((low - int64_t(1)) >> shift, int64_t(0), last));
}
HPSF_FN int LastCellOf(int64_t high, int shift, int64_t last) { return int(clamp(high >> shift, int64_t(0), last)); }

HPSF_FN CellRange TriangleCellRange(FixedPoint3 v0, FixedPoint3 v1, FixedPoint3 v2, int level, int resolution_log2) {
  int shift = kOccupancyFractionBits + level;
  int64_t last = (int64_t(1) << (resolution_log2 - level)) - int64_t(1);
  CellRange r;
  r.x0 = FirstCellOf(FixedMin3(v0.x, v1.x, v2.x), shift, last);
  r.y0 = FirstCellOf(FixedMin3(v0.y, v1.y, v2.y), shift, last);
  r.z0 = FirstCellOf(FixedMin3(v0.z, v1.z, v2.z), shift, last);
  r.x1 = LastCellOf(FixedMax3(v0.x, v1.x, v2.x), shift, last);
  r.y1 = LastCellOf(FixedMax3(v0.y, v1.y, v2.y), shift, last);
  r.z1 = LastCellOf(FixedMax3(v0.z, v1.z, v2.z), shift, last);
  return r;
}

// The field of a level holds at least 4 cells per axis: a level of fewer uses the corner of a 4 x 4 x 4 field.
HPSF_FN int OccupancyFieldLog2(int resolution_log2, int level) {
  return max(resolution_log2 - level, kMinOccupancyResolutionLog2);
}

// The word of the bit field that holds cell (cx, cy, cz) of a level of 2^resolution_log2 cells per axis, and its bit:
// blocks of 4 (x) by 4 (y) by 2 (z) cells, x fastest, then y, then z.
HPSF_FN uint OccupancyWord(int cx, int cy, int cz, int resolution_log2) {
  uint blocks_log2 = uint(resolution_log2 - 2);
  return uint(cx >> 2) | (uint(cy >> 2) << blocks_log2) | (uint(cz >> 1) << (2u * blocks_log2));
}
HPSF_FN uint OccupancyBit(int cx, int cy, int cz) { return uint(cx & 3) | (uint(cy & 3) << 2) | (uint(cz & 1) << 4); }
// The words of the field: 2^(3L - 5).
HPSF_FN uint OccupancyWords(int resolution_log2) { return 1u << uint(3 * resolution_log2 - 5); }

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_OCCUPANCY_H
