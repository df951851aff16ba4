// The stable buffer interface of the Vulkan hash table (README, "The Vulkan backend"): every accumulate shader,
// ours or a user's (--accumulate-spv), sees these bindings in descriptor set 0 and these push constants, and
// the host reads the table back from them and judges it with the table checker.
//   0 records     uniform texel buffer, RGBA32UI, 9 texels per record (record_texels.glsl)   read
//   1 keys        uvec4[3 n]: KeyResult per record (key words, slot0, fingerprint, level, status) write
//   2 tags        uint[capacity] (fingerprints) or uint64_t[capacity] (full keys), zeroed      atomics
//   3 sums        uint64_t[3 capacity] (fixed64), float[3 capacity] (float32) or uint[3 capacity]
//                 (packed-decimal, core/shared/packed_sums.h), slot * 3 + c, zeroed
//   4 counts      uint64_t[capacity]; packed-decimal: uint[capacity], the count word; zeroed   atomics
//   5 placements  uint[n]: slot, kPlacementProbeFailure or kPlacementNotPlaced                write
//   6 stats       uint64_t wraps: integer adds whose sum wrapped; then uint64_t count_wraps:  atomics
//                 adds whose count wrapped (docs/design/defects.md, D12); both zeroed
//   7 accepted    uint[n]: 1 when the record passed the host's input checks (a shader never sees NaN)
//   8 last_seen   uint[capacity]: with table.track_last_seen, the frame a record was last added    write
//   9 previous_sums    as sums: with table.blending, the table before the frame (for reading only;   -
//  10 previous_counts  as counts           the blend pass after the accumulate reads them)        -
//  11 squares     as sums, one per slot: with --second-moments, the sum of squared brightness     atomics
//                 (core/shared/second_moment.h; fixed64 at 2^G), zeroed
//  12 square_params  uint keeps_squares (1 with --second-moments), int square_bits (G)          read
// Push constants: KeyParams (64 bytes), then TableParams (32 bytes: the table's shape, F, the frame state, and
// claim_tombstones: with priority eviction, slots tagged kTombstoneTag may be claimed), then
// TemporalParams (24 bytes, core/shared/temporal_blend.h: the blend's mode, with table.blending).
// A shader written against the first 8 bindings and 16 bytes of TableParams still runs without eviction; one that
// declares nothing past TableParams runs with every option. Bindings 9 and 10 and TemporalParams are declared
// for an includer that defines HPSF_TABLE_INTERFACE_TEMPORAL (its shader then needs 64-bit floats).
// The includer defines HPSF_SUMS_TYPE (uint64_t, float or uint) and, for packed-decimal's count word, HPSF_COUNT_TYPE
// uint (uint64_t otherwise). A shader that declares neither binding 11 nor 12 runs without --second-moments (with it,
// the checker finds its square sums zero).
#ifndef HPSF_COUNT_TYPE
#define HPSF_COUNT_TYPE uint64_t
#endif
#define HPSF_RECORDS_BINDING 0
#include "record_texels.glsl"

layout(std430, binding = 1) writeonly buffer Keys { uvec4 key_vectors[]; };
layout(std430, binding = 2) buffer Tags { uint tags[]; };
// The same buffer, with params.key_identity kIdentityFull: 64-bit tags (slot_tags.glsl).
layout(std430, binding = 2) buffer FullTags { uint64_t full_tags[]; };
layout(std430, binding = 3) buffer Sums { HPSF_SUMS_TYPE sums[]; };
layout(std430, binding = 4) buffer Counts { HPSF_COUNT_TYPE counts[]; };
layout(std430, binding = 5) writeonly buffer Placements { uint placements[]; };
layout(std430, binding = 6) buffer Stats {
  uint64_t wraps;
  uint64_t count_wraps;
};
layout(std430, binding = 7) readonly buffer Accepted { uint accepted[]; };
layout(std430, binding = 8) writeonly buffer LastSeen { uint last_seen[]; };
layout(std430, binding = 11) buffer Squares { HPSF_SUMS_TYPE squares[]; };
layout(std430, binding = 12) readonly buffer SquareParams {
  uint keeps_squares;
  int square_bits;
};
#if defined(HPSF_TABLE_INTERFACE_TEMPORAL)
layout(std430, binding = 9) readonly buffer PreviousSums { HPSF_SUMS_TYPE previous_sums[]; };
layout(std430, binding = 10) readonly buffer PreviousCounts { HPSF_COUNT_TYPE previous_counts[]; };
layout(push_constant) uniform Params {
  KeyParams params;
  TableParams table;
  TemporalParams temporal;
};
#else
layout(push_constant) uniform Params {
  KeyParams params;
  TableParams table;
};
#endif

// KeyResult as three uvec4: one store per vector instead of one per word.
void StoreKeyResult(uint i, KeyResult k) {
  uint first = i * 3u;
  key_vectors[first] = uvec4(k.words.cell_x, k.words.cell_y, k.words.cell_z, k.words.level);
  key_vectors[first + 1u] = uvec4(k.words.normal, k.words.extra, k.slot0, k.fingerprint);
  key_vectors[first + 2u] = uvec4(uint(k.level), k.status, k.identity_high, k.padding1);
}
