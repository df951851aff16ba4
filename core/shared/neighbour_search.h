// Neighbourhood search (Binder et al. §3.3.1), written once for C++ and GLSL: a record whose chosen cell (its own, or
// the level core/shared/levels.h chose) holds fewer than min_count samples also reads the cells of the same level
// nearest its jittered position, the 2^3 stencil: per axis its own cell and the neighbour on the side of the cell's
// centre the position lies on. Eight cells around the position cover the same volume as the next coarser cell, but
// centred on the record rather than aligned to the grid, so for the same count they average over points nearer the
// record than the coarser level does; the 3^3 stencil reads 27 cells, the 19 beyond the 2^3 all farther from the
// position. The resolve averages the cells it found by count: their sums added, divided by their counts added.
// Only the resolve reads them (D10): a lookup never claims a slot, and passes tombstones.
#ifndef HPSF_CORE_SHARED_NEIGHBOUR_SEARCH_H
#define HPSF_CORE_SHARED_NEIGHBOUR_SEARCH_H

#include "cell.h"
#include "key.h"
#include "key_words.h"
#include "lookup.h"

HPSF_SHARED_BEGIN

const uint kStencilCells = 8u;  // corner 0 the cell itself; bit a of a corner: the neighbour along axis a

// Per axis, the side of its cell's centre a position lies on: 1 the upper half (its neighbour at +1), 0 the lower
// (at -1). At the record's own level, from the fraction q - floor(q) of its cell coordinates (exact: q and floor(q)
// share an exponent, and floor, never truncation, so negative coordinates have their fraction in [0, 1) too).
HPSF_FN uvec3 StencilSidesAtOwnLevel(KeyPosition at) {
  vec3 q = CellCoordinates(at.jittered, at.inverse_size);
  HPSF_PRECISE vec3 fraction = q - floor(q);
  return uvec3(fraction.x >= 0.5f ? 1u : 0u, fraction.y >= 0.5f ? 1u : 0u, fraction.z >= 0.5f ? 1u : 0u);
}

// k levels up (k >= 1) the side follows from the own cell's words: cells nest (core/shared/levels.h), so the own
// cell's bit k - 1 says which half of the coarser cell holds it.
HPSF_FN uvec3 StencilSidesAtLevel(uvec3 own_sides, KeyWords own, uint k) {
  if (k == 0u) return own_sides;
  return uvec3(uint(int(own.cell_x) >> (k - 1u)) & 1u, uint(int(own.cell_y) >> (k - 1u)) & 1u,
               uint(int(own.cell_z) >> (k - 1u)) & 1u);
}

// The words of a stencil corner around `cell` (the chosen level's). Cells lie in (-2^31, 2^31) with room to spare
// (core/shared/cell.h: |q| < 2^31 and floats near 2^31 are 256 apart), so a neighbour's word never wraps.
HPSF_FN KeyWords StencilCellWords(KeyWords cell, uvec3 sides, uint corner) {
  KeyWords w = cell;
  if ((corner & 1u) != 0u) w.cell_x = sides.x != 0u ? cell.cell_x + 1u : cell.cell_x - 1u;
  if ((corner & 2u) != 0u) w.cell_y = sides.y != 0u ? cell.cell_y + 1u : cell.cell_y - 1u;
  if ((corner & 4u) != 0u) w.cell_z = sides.z != 0u ? cell.cell_z + 1u : cell.cell_z - 1u;
  return w;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_NEIGHBOUR_SEARCH_H
