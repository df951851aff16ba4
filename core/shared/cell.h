// The voxel of a (jittered) position: q = x' * (1 / cell size), then floor, never truncation. A position whose
// |q| reaches 2^31 in any axis (or is not finite) has no int32 cell: the record is unkeyable.
#ifndef HPSF_CORE_SHARED_CELL_H
#define HPSF_CORE_SHARED_CELL_H

#include "float_bits.h"

HPSF_SHARED_BEGIN

const float kCellLimit = 2147483648.0f;  // 2^31

struct Cell {
  ivec3 index;
  bool keyable;
};

// inverse_size is 2^-l under level of detail (then the product is exact unless it leaves the normal range)
// or the host's correctly rounded 1 / cell_size.
// The position in units of the cell size, before the floor: q.
HPSF_FN vec3 CellCoordinates(vec3 position, float inverse_size) {
  HPSF_PRECISE vec3 q = Flush(position * inverse_size);
  return q;
}

HPSF_FN Cell CellOf(vec3 position, float inverse_size) {
  vec3 q = CellCoordinates(position, inverse_size);
  Cell c;
  // Checked on the float before conversion; NaN fails the comparison and so is unkeyable too.
  c.keyable = all(lessThan(abs(q), vec3(kCellLimit)));
  c.index = c.keyable ? ivec3(floor(q)) : ivec3(0);
  return c;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_CELL_H
