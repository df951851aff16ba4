// Resolution changes across frames (Binder et al. §3.4.2; core/level_seed.h), written once for C++ and GLSL: the
// cells of the neighbouring levels whose estimate seeds a cell new in a frame. A cell at level l holds the points x
// with floor(x 2^-l) = (x, y, z), so its parent at l + 1 is (x >> 1, y >> 1, z >> 1) (arithmetic shifts round
// down, as floor does) and its 8 children at l - 1 are (2x + dx, 2y + dy, 2z + dz); the normal bucket is kept.
// Word arithmetic wraps, as the key words do: a child beyond 2^31 names no cell any record has.
#ifndef HPSF_CORE_SHARED_LEVEL_SEED_H
#define HPSF_CORE_SHARED_LEVEL_SEED_H

#include "float_bits.h"
#include "key_words.h"

HPSF_SHARED_BEGIN

const uint kLevelSeedChildren = 8u;

// Child 0..7 of a cell: bit 0 the x half, bit 1 y, bit 2 z.
HPSF_FN KeyWords ChildKeyWords(KeyWords w, uint child) {
  KeyWords c = w;
  c.cell_x = w.cell_x * 2u + (child & 1u);
  c.cell_y = w.cell_y * 2u + ((child >> 1u) & 1u);
  c.cell_z = w.cell_z * 2u + (child >> 2u);
  c.level = w.level - 1u;
  return c;
}

HPSF_FN KeyWords ParentKeyWords(KeyWords w) {
  KeyWords p = w;
  p.cell_x = uint(int(w.cell_x) >> 1);
  p.cell_y = uint(int(w.cell_y) >> 1);
  p.cell_z = uint(int(w.cell_z) >> 1);
  p.level = w.level + 1u;
  return p;
}

// The cell k levels above (ParentKeyWords k times): multi-level accumulation's coarser cells (core/shared/levels.h).
HPSF_FN KeyWords CoarserKeyWords(KeyWords w, uint k) {
  KeyWords c = w;
  c.cell_x = uint(int(w.cell_x) >> k);
  c.cell_y = uint(int(w.cell_y) >> k);
  c.cell_z = uint(int(w.cell_z) >> k);
  c.level = w.level + k;
  return c;
}

// The first candidate slot of that cell (core/shared/key_words.h's index hash), for the passes that walk a coarser
// cell's window from its own key words.
HPSF_FN uint Slot0AtLevel(KeyWords own, uint k, uint normal_in_index, uint capacity_mask) {
  return IndexHash(CoarserKeyWords(own, k), normal_in_index) & capacity_mask;
}

// The parent's share that seeds a child: its sums and count shifted right by 3 + shift (an eighth of the parent, as
// its volume splits in 8, weighted 2^-shift: Binder's compromise between less variance and a visible coarse
// estimate). Exact in fixed64 (a shift) and in float32 (a power of two, far from the subnormals for radiance).
HPSF_FN uint64_t ParentShareOfCount(uint64_t count, uint shift) { return count >> (3u + shift); }
HPSF_FN uint64_t ParentShareOfFixedSum(uint64_t sum, uint shift) { return sum >> (3u + shift); }
HPSF_FN float ParentShareOfFloatSum(float sum, uint shift) { return sum * PowerOfTwo(-int(3u + shift)); }

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_LEVEL_SEED_H
