#version 450
// The temporal blend after a frame's accumulate (core/temporal.h; the emulator's emulated/temporal_kernel.h holds
// the rule): one invocation per slot. A slot that held samples in the previous table (the double buffer the host
// copied the table into before the accumulate, read here and written by no pass of the frame) and that the frame
// added to is blended by core/shared/temporal_blend.h, in double, as C++ blends it; every other slot keeps what it
// holds. With packed-decimal sums (core/shared/packed_sums.h) the sums are 32-bit words and the counts count words,
// whose frame counter the blend keeps; the settle after it halves and advances. The test suite compiles it once
// more per defect, run through --temporal-spv as a team's own would be:
// HPSF_DEFECT_BLEND_UNTOUCHED, a slot the frame did not touch blended too (its history decays with no sample);
// HPSF_DEFECT_TRUNCATED_BLEND, the fixed64 blend truncated instead of rounded half to even.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "float_controls_fp64.glsl"
#include "../../core/shared/packed_sums.h"
#include "../../core/shared/temporal_blend.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer SumWords { uint sum_words[]; };  // the sums, as 32-bit words
layout(std430, binding = 1) buffer Counts { uint64_t counts[]; };
layout(std430, binding = 1) buffer CountWords { uint count_words[]; };  // the same buffer, with packed
layout(std430, binding = 2) readonly buffer PreviousSumWords { uint previous_sum_words[]; };
layout(std430, binding = 3) readonly buffer PreviousCounts { uint64_t previous_counts[]; };
layout(std430, binding = 3) readonly buffer PreviousCountWords { uint previous_count_words[]; };  // with packed
// Bindings 4 and 5, with --compaction occupied-list (compacted): one invocation per entry of the list.
layout(std430, binding = 4) readonly buffer Occupied { uint occupied[]; };
layout(std430, binding = 5) readonly buffer OccupiedHeader { uint occupied_count; };
// Bindings 6 and 7, with --second-moments: the square sums (core/shared/second_moment.h) and their double buffer, as
// 32-bit words: two per slot (fixed64) or one (float32).
layout(std430, binding = 6) buffer SquareWords { uint square_words[]; };
layout(std430, binding = 7) readonly buffer PreviousSquareWords { uint previous_square_words[]; };
layout(push_constant) uniform Params {  // vulkan_filter.cpp's TemporalPush
  TemporalParams temporal;
  uint capacity;
  uint fixed64;    // 1: sums are 64-bit fixed point (two words per channel); 0: float32 or packed-decimal
  uint compacted;  // 1: dispatched indirectly, one invocation per entry of the occupied list (core/compaction.h)
  uint packed;     // 1: packed-decimal, 32-bit integer sums and count words
  uint squares;    // 1 with --second-moments: the square sums blend with the sums
  uint reserved;
};

// A slot's square sum as a double, and the frame's part of it: an exact integer difference in fixed64, a float
// subtraction in float32, as core's BlendCellState.
double SquareAt(uint slot, bool previous) {
  if (fixed64 != 0u) {
    uvec2 words = previous ? uvec2(previous_square_words[slot * 2u], previous_square_words[slot * 2u + 1u])
                           : uvec2(square_words[slot * 2u], square_words[slot * 2u + 1u]);
    return double(packUint2x32(words));
  }
  return double(uintBitsToFloat(previous ? previous_square_words[slot] : square_words[slot]));
}
double FrameSquare(uint slot) {
  if (fixed64 != 0u) {
    uint64_t now = packUint2x32(uvec2(square_words[slot * 2u], square_words[slot * 2u + 1u]));
    uint64_t before = packUint2x32(uvec2(previous_square_words[slot * 2u], previous_square_words[slot * 2u + 1u]));
    return double(now - before);
  }
  float difference = uintBitsToFloat(square_words[slot]) - uintBitsToFloat(previous_square_words[slot]);
  return double(difference);
}

// A slot's count word (packed-decimal) or count, as 64 bits: compared whole to see whether the frame touched it.
uint64_t CountWordAt(uint slot, bool previous) {
  if (packed != 0u) return uint64_t(previous ? previous_count_words[slot] : count_words[slot]);
  return previous ? previous_counts[slot] : counts[slot];
}
uint64_t CountOf(uint64_t word) { return packed != 0u ? uint64_t(PackedCount(uint(word))) : word; }

double SumAt(uint slot, int c, bool previous) {
  if (fixed64 != 0u) {
    uint w = (slot * 3u + uint(c)) * 2u;
    uvec2 words = previous ? uvec2(previous_sum_words[w], previous_sum_words[w + 1u])
                           : uvec2(sum_words[w], sum_words[w + 1u]);
    return double(packUint2x32(words));
  }
  uint w = slot * 3u + uint(c);
  uint word = previous ? previous_sum_words[w] : sum_words[w];
  return packed != 0u ? double(word) : double(uintBitsToFloat(word));
}

void Blend(uint slot) {
  uint64_t old_word = CountWordAt(slot, true);
  uint64_t old_count = CountOf(old_word);
  if (old_count == 0ul) return;  // a new cell, or none: nothing to blend
  uint64_t word = CountWordAt(slot, false);
#if !defined(HPSF_DEFECT_BLEND_UNTOUCHED)
  if (word == old_word) return;  // the frame did not touch it
#endif
  dvec3 old_sum, frame_sum;
  for (int c = 0; c < 3; ++c) {
    old_sum[c] = SumAt(slot, c, true);
    // The frame's sums: an exact integer difference in fixed64, a float subtraction in float32, as core's.
    if (fixed64 != 0u) {
      uint w = (slot * 3u + uint(c)) * 2u;
      uint64_t now = packUint2x32(uvec2(sum_words[w], sum_words[w + 1u]));
      uint64_t before = packUint2x32(uvec2(previous_sum_words[w], previous_sum_words[w + 1u]));
      frame_sum[c] = double(now - before);
    } else if (packed != 0u) {  // a 32-bit difference, exact while the frame's adds stayed below 2^32
      uint w = slot * 3u + uint(c);
      frame_sum[c] = double(sum_words[w] - previous_sum_words[w]);
    } else {
      uint w = slot * 3u + uint(c);
      float difference = uintBitsToFloat(sum_words[w]) - uintBitsToFloat(previous_sum_words[w]);
      frame_sum[c] = double(difference);
    }
  }
  // packed-decimal's count modulo its 24 bits, as core's BlendCellState.
  uint64_t frame_count = packed != 0u ? uint64_t((uint(word) - uint(old_word)) & kPackedCountMask) : word - old_word;
  double old_square = squares != 0u ? SquareAt(slot, true) : 0.0;
  double frame_square = squares != 0u ? FrameSquare(slot) : 0.0;
  TemporalBlend b = BlendCell(temporal, old_sum, old_count, frame_sum, frame_count, old_square, frame_square);
  if (b.integrated) return;
  if (squares != 0u) {
    double square = BlendSquare(b, old_square, old_count, frame_square, frame_count);
    if (fixed64 != 0u) {
      uvec2 words = unpackUint2x32(uint64_t(RoundHalfEvenNonNegative(square)));
      square_words[slot * 2u] = words.x;
      square_words[slot * 2u + 1u] = words.y;
    } else {
      square_words[slot] = floatBitsToUint(float(square));
    }
  }
  for (int c = 0; c < 3; ++c) {
    if (fixed64 != 0u) {
#if defined(HPSF_DEFECT_TRUNCATED_BLEND)
      uvec2 words = unpackUint2x32(uint64_t(b.sum[c]));
#else
      uvec2 words = unpackUint2x32(uint64_t(RoundHalfEvenNonNegative(b.sum[c])));
#endif
      uint w = (slot * 3u + uint(c)) * 2u;
      sum_words[w] = words.x;
      sum_words[w + 1u] = words.y;
    } else if (packed != 0u) {  // modulo 2^32, as core's: the blend stays below 2^64
      sum_words[slot * 3u + uint(c)] = uint(uint64_t(RoundHalfEvenNonNegative(b.sum[c])));
    } else {
      sum_words[slot * 3u + uint(c)] = floatBitsToUint(float(b.sum[c]));
    }
  }
  if (packed != 0u) {
    count_words[slot] = PackCountWord(uint(b.count) & kPackedCountMask, PackedFrames(uint(word)));
  } else {
    counts[slot] = b.count;
  }
}

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  uint steps = compacted != 0u ? occupied_count : capacity;
  for (uint step = gl_GlobalInvocationID.x; step < steps; step += stride) Blend(compacted != 0u ? occupied[step] : step);
}
