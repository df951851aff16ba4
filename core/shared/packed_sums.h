// Packed decimal sums (--accum packed-decimal), the layout NVIDIA SHaRC keeps: per slot four 32-bit words, three
// channel sums, to which each record adds its channel times 1000 rounded half to even (ToFixedPoint at scale 1000),
// and a fourth that packs the record count (bits 0-23) with the frames the cell has lived (bits 24-31, saturating).
// Every word wraps at 32 bits, as a GPU's 32-bit atomics do: nothing here hides an overflow, the table checker
// recomputes the words exactly and names a wrapped one (docs/design/algorithm.md#packed-decimal-sums).
//
// The layout's overflow rule is the settle, a pass over slots after each frame's accumulate: a live slot's frame
// counter advances, and a slot whose count passed kPackedHalvingCount, or one of whose sums reached
// kPackedHalvingSum, is halved, which keeps the next frame's adds room to land without wrapping.
#ifndef HPSF_CORE_SHARED_PACKED_SUMS_H
#define HPSF_CORE_SHARED_PACKED_SUMS_H

#include "prelude.h"

HPSF_SHARED_BEGIN

const float kPackedDecimalScale = 1000.0f;  // SHaRC's radiance scale (once 1e4)
const uint kPackedCountBits = 24u;
const uint kPackedCountMask = 0x00FFFFFFu;
const uint kPackedFramesMax = 255u;
// A count above 2^20 halves: 2^24 - 2^20 adds of room are left for the next frame before the count carries into
// the frame counter. A sum at or above 2^31 halves: 2^31 is left for the next frame's adds.
const uint kPackedHalvingCount = 0x00100000u;
const uint kPackedHalvingSum = 0x80000000u;

HPSF_FN uint PackedCount(uint word) { return word & kPackedCountMask; }
HPSF_FN uint PackedFrames(uint word) { return word >> kPackedCountBits; }
HPSF_FN uint PackCountWord(uint count, uint frames) { return (frames << kPackedCountBits) | count; }

// x / 2 rounded half to even, exactly: 3 -> 2, 5 -> 2, 1 -> 0 (a sum).
HPSF_FN uint HalveToEven(uint x) { return (x >> 1u) + (x & (x >> 1u) & 1u); }
// x / 2 rounded up, so a live cell's count never halves to 0, which would make it a tombstone.
HPSF_FN uint HalveUp(uint x) { return (x >> 1u) + (x & 1u); }

HPSF_FN bool PackedNeedsHalving(uvec4 cell) {
  return PackedCount(cell.w) > kPackedHalvingCount || cell.x >= kPackedHalvingSum || cell.y >= kPackedHalvingSum ||
         cell.z >= kPackedHalvingSum;
}

// The settle of one slot: (sum r, sum g, sum b, count word) before and after. A slot with no samples (empty, or a
// tombstone) is left as it is.
HPSF_FN uvec4 SettlePacked(uvec4 cell) {
  uint count = PackedCount(cell.w);
  if (count == 0u) return cell;
  uint frames = min(PackedFrames(cell.w) + 1u, kPackedFramesMax);
  if (PackedNeedsHalving(cell)) {
    cell.x = HalveToEven(cell.x);
    cell.y = HalveToEven(cell.y);
    cell.z = HalveToEven(cell.z);
    count = HalveUp(count);
  }
  cell.w = PackCountWord(count, frames);
  return cell;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_PACKED_SUMS_H
