// The resolve pass (docs/design/algorithm.md), a separate pass after accumulate, pixel by pixel, no atomics: each
// record's value is radiance_before + throughput * the average of its slot (sum / count), or its own
// contribution without a slot, or radiance_before alone without a vertex; the pixel is the mean of its
// records in sample order. In double, operation for operation as core/resolve.cpp, so that with the same table
// the image is the same bits. resolve_fixed64.comp, resolve_float32.comp and resolve_packed_decimal.comp define the
// sums type (and packed-decimal the count word's, HPSF_COUNT_TYPE uint). The test suite
// compiles it once more per defect (HPSF_DEFECT_AVERAGE_OFF_BY_ONE, HPSF_DEFECT_AVERAGE_IN_FLOAT,
// HPSF_DEFECT_LEVEL_WRONG_COUNT, and the neighbourhood search's HPSF_DEFECT_SEARCH_CLAIMS,
// HPSF_DEFECT_SEARCH_STOPS_AT_TOMBSTONE, HPSF_DEFECT_STENCIL_TRUNCATED), run through --resolve-spv as a team's own
// resolve would be. Compiled with HPSF_NEIGHBOUR_SEARCH (resolve_search_*.comp, run with --neighbour-search on), a
// record whose chosen cell holds fewer than min_count samples also reads the stencil's cells found by lookup
// (core/shared/neighbour_search.h), and averages them all by count; without it the pass has no search to skip.
// hpsf's own resolve with the search is two passes, so that the lanes that search run side by side instead of
// holding up a subgroup whose other lanes do not: the first (HPSF_DEFER_SEARCH, resolve_defer_*.comp) resolves every
// pixel none of whose records searches and lists the others, with the indirect dispatch of the second
// (HPSF_SEARCH_DEFERRED_PIXELS, resolve_search_*.comp), which resolves the listed pixels with the search, one per
// invocation. Both run ResolvePixel, so a pixel's bits do not depend on which pass wrote it; with no record below the
// threshold the second pass is dispatched with no workgroup.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#if defined(HPSF_DEFECT_SEARCH_CLAIMS)
#extension GL_EXT_shader_atomic_int64 : require
#endif
// The search's broken variants search, and so does the second pass over the listed pixels.
#if defined(HPSF_DEFECT_SEARCH_CLAIMS) || defined(HPSF_DEFECT_SEARCH_STOPS_AT_TOMBSTONE) || \
    defined(HPSF_DEFECT_STENCIL_TRUNCATED) || defined(HPSF_SEARCH_DEFERRED_PIXELS)
#define HPSF_NEIGHBOUR_SEARCH
#endif
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "float_controls_fp64.glsl"
#include "../../core/shared/record_layout.h"
#include "../../core/shared/table_params.h"
#include "../../core/shared/packed_sums.h"
#include "../../core/shared/levels.h"
#if defined(HPSF_NEIGHBOUR_SEARCH)
#include "../../core/shared/eviction_priority.h"
#include "../../core/shared/lookup.h"
#include "../../core/shared/neighbour_search.h"
#include "../../core/shared/probe_scheme.h"
#endif
#ifndef HPSF_COUNT_TYPE
#define HPSF_COUNT_TYPE uint64_t
#endif
#include "subgroup_runs.glsl"
#include "../../core/shared/cell_interpolation.h"

#define HPSF_RECORDS_BINDING 0
#include "record_texels.glsl"

// The host dispatches ceil(pixels / (64 * 16)) workgroups, at most 65535 (vulkan/vulkan_filter.cpp).
const uint kPixelsPerInvocation = 16u;
layout(local_size_x = 64) in;

layout(std430, binding = 1) readonly buffer Sums { HPSF_SUMS_TYPE sums[]; };
layout(std430, binding = 2) readonly buffer Counts { HPSF_COUNT_TYPE counts[]; };
layout(std430, binding = 3) readonly buffer Placements { uint placements[]; };
layout(std430, binding = 4) readonly buffer Accepted { uint accepted[]; };
layout(std430, binding = 5) writeonly buffer Pixels { float pixels[]; };  // RGB per pixel
// --interpolation (core/shared/cell_interpolation.h): the square sums as the accumulate's binding 11 left them (two
// 32-bit words a slot, low first, fixed64; one float's bits, float32), and the rule.
layout(std430, binding = 9) readonly buffer SquareWords { uint square_words[]; };
layout(std430, binding = 10) readonly buffer Interpolation {  // vulkan_filter.cpp's InterpolationParams
  double interpolation_v0;
  double interpolation_v1;
  double square_unscale;  // 2^-G, fixed64
  uint interpolation_function;  // kInterpolationOff, kInterpolationStep, kInterpolationSmooth or kInterpolationPath
  uint own_lights;              // 1: a record's own light is binding 11's, else its contribution
};
// Adaptive path graphs (core/path_graph.h): each pixel record's own light, where it differs from the contribution its
// cell added (RecordBatch::own_light, rgb and a 0).
layout(std430, binding = 11) readonly buffer OwnLights { vec4 own_light[]; };
// The tags, for the search's lookups (slot_tags.glsl): 32-bit fingerprints or 64-bit full keys.
#if !defined(HPSF_NEIGHBOUR_SEARCH)
#elif defined(HPSF_DEFECT_SEARCH_CLAIMS)
layout(std430, binding = 6) buffer Tags { uint tags[]; };
layout(std430, binding = 6) buffer FullTags { uint64_t full_tags[]; };
#else
layout(std430, binding = 6) readonly buffer Tags { uint tags[]; };
layout(std430, binding = 6) readonly buffer FullTags { uint64_t full_tags[]; };
#define HPSF_TAGS_READONLY
#endif
#if defined(HPSF_NEIGHBOUR_SEARCH)
#include "slot_tags.glsl"
#endif
// The pixels the first pass left to the search, and the second pass's VkDispatchIndirectCommand at byte 4 (three
// uints, not a uvec3: std430 would align that to 16). The host sets the count and groups_x to 0, the others to 1.
#if defined(HPSF_DEFER_SEARCH)
layout(std430, binding = 7) writeonly buffer DeferredPixels { uint deferred_pixels[]; };
layout(std430, binding = 8) buffer DeferredHeader {
#elif defined(HPSF_SEARCH_DEFERRED_PIXELS)
layout(std430, binding = 7) readonly buffer DeferredPixels { uint deferred_pixels[]; };
layout(std430, binding = 8) readonly buffer DeferredHeader {
#endif
#if defined(HPSF_DEFER_SEARCH) || defined(HPSF_SEARCH_DEFERRED_PIXELS)
  uint deferred_count;
  uint groups_x;
  uint groups_y;
  uint groups_z;
};
const uint kSearchPixelsPerWorkgroup = 64u;  // the second pass's local_size_x, one pixel per invocation
const uint kMaxWorkgroups = 65535u;          // its loop strides over the rest
#endif

struct ResolveParams {  // vulkan_filter.cpp's ResolvePush
  double unscale;  // 2^-F, fixed64
  uint capacity;
  uint pixel_count;
  uint samples_per_pixel;
  uint levels;     // the placements hold `levels` words per record, level-major (core/shared/levels.h)
  uint min_count;  // the resolve reads a record's finest level whose count reaches it, else its coarsest
  uint neighbour_search;  // 1: a record below min_count also reads its stencil (core/shared/neighbour_search.h)
};
struct SearchParams {  // vulkan_filter.cpp's ResolvePush, after the key's parameters
  uint probe_limit;
  uint probe_scheme;        // kProbeLinear, kProbeBucket or kProbeBucketWindow
  uint defer_every_pixel;   // 1: the first pass lists every pixel (--force-effect neighbour-search)
  uint reserved;
};
// A resolve written against the first 32 bytes runs without the search.
#if defined(HPSF_NEIGHBOUR_SEARCH) || defined(HPSF_DEFER_SEARCH)
layout(push_constant) uniform Params {
  ResolveParams params;
  KeyParams key;  // the key path's, to compute a searching record's position again
  SearchParams search;
};
#else
layout(push_constant) uniform Params { ResolveParams params; };
#endif

dvec3 D(vec4 v) { return dvec3(double(v.x), double(v.y), double(v.z)); }

uint64_t SlotCount(uint slot) {
#ifdef HPSF_PACKED_DECIMAL
  return uint64_t(PackedCount(counts[slot]));
#else
  return uint64_t(counts[slot]);
#endif
}

// The slot record i reads: its finest placed level whose count reaches min_count (core/shared/levels.h).
LevelChoice ResolvedSlot(uint i, ResolveParams p) {
  uint records = p.pixel_count * p.samples_per_pixel;
  LevelChoice choice = NoLevelChosen();
  for (uint level = 0u; level < p.levels; ++level) {
    uint slot = placements[LevelPlacementIndex(i, level, records)];
#if defined(HPSF_DEFECT_LEVEL_WRONG_COUNT)  // each level judged by the count of the record's own cell
    uint own = placements[i];
    uint64_t count = own < p.capacity ? SlotCount(own) : 0ul;
#else
    uint64_t count = slot < p.capacity ? SlotCount(slot) : 0ul;
#endif
    choice = ChooseLevel(choice, level, slot, count, p.capacity, p.min_count);
  }
  return choice;
}

// A slot's sums as the resolve adds them: integers exactly, float32 sums in double
// (core/neighbour_search.h's StencilTotal).
#if defined(HPSF_FIXED64) || defined(HPSF_PACKED_DECIMAL)
#define HPSF_TOTAL_TYPE u64vec3
#else
#define HPSF_TOTAL_TYPE dvec3
#endif
HPSF_TOTAL_TYPE SlotSums(uint slot) {
  uint first = slot * 3u;
  return HPSF_TOTAL_TYPE(sums[first], sums[first + 1u], sums[first + 2u]);
}

#if defined(HPSF_NEIGHBOUR_SEARCH)
// The slot holding the words' identity with samples, found by lookup (core/shared/lookup.h), or capacity.
uint LookUp(KeyWords words, KeyParams k, SearchParams s, uint capacity) {
  StoredIdentity identity = IdentityOfWords(words, k.key_identity, k.fingerprint_bits);
  if (!identity.fits) return capacity;
  uint slot0 = IndexHash(words, k.normal_in_index) & k.capacity_mask;
  uint64_t wanted = IdentityValue(identity.words);
  bool full = k.key_identity == kIdentityFull;
  ProbeScheme scheme = MakeProbeScheme(s.probe_scheme, capacity, s.probe_limit);
  for (uint probe = 0u; probe < s.probe_limit; ++probe) {
    uint slot = CandidateSlot(scheme, slot0, probe);
    uint64_t tag = LoadTag(slot, full);
#if defined(HPSF_DEFECT_SEARCH_CLAIMS)  // the first empty slot claimed, as an insertion would
    if (tag == 0ul) {
      SwapTag(slot, 0ul, wanted, full);
      return capacity;
    }
#endif
#if defined(HPSF_DEFECT_SEARCH_STOPS_AT_TOMBSTONE)  // an eviction's tombstone taken for an empty slot
    if (tag == uint64_t(kTombstoneTag)) return capacity;
#endif
    uint step = LookupStep(tag, wanted, SlotCount(slot));
    if (step == kLookupEnd) break;
    if (step == kLookupFound) return slot;
  }
  return capacity;
}

// Adds to record i's sums and count those of the stencil's slots found around its chosen level, in corner order.
void AddNeighbours(uint i, LevelChoice chosen, ResolveParams p, inout HPSF_TOTAL_TYPE total, inout uint64_t count) {
  KeyParams k = key;
  SearchParams s = search;
  Record r = LoadRecord(i);
  KeyPosition at = JitteredKeyPosition(k, r);  // the jitter once, for the key and the side
  KeyResult own = KeyAtPosition(k, r, at);
#if defined(HPSF_DEFECT_STENCIL_TRUNCATED)  // the side from q - trunc(q): below zero, the wrong neighbour
  vec3 q = CellCoordinates(at.jittered, at.inverse_size);
  vec3 fraction = q - trunc(q);
  uvec3 own_sides = uvec3(fraction.x >= 0.5 ? 1u : 0u, fraction.y >= 0.5 ? 1u : 0u, fraction.z >= 0.5 ? 1u : 0u);
#else
  uvec3 own_sides = StencilSidesAtOwnLevel(at);
#endif
  uvec3 sides = StencilSidesAtLevel(own_sides, own.words, chosen.level);
  KeyWords cell = KeyAtLevel(k, own, chosen.level).words;
  for (uint corner = 1u; corner < kStencilCells; ++corner) {
    uint slot = LookUp(StencilCellWords(cell, sides, corner), k, s, p.capacity);
    if (slot < p.capacity) {
      total += SlotSums(slot);
      count += SlotCount(slot);
    }
  }
}
#endif

#if defined(HPSF_DEFER_SEARCH)
bool defer_every_pixel = false;  // from the push constants, once per invocation

// Lists the pixel for the second pass; the entry that starts a workgroup's share adds the workgroup.
void DeferPixel(uint pixel) {
  uint entry = atomicAdd(deferred_count, 1u);
  deferred_pixels[entry] = pixel;
  if (entry % kSearchPixelsPerWorkgroup == 0u && entry / kSearchPixelsPerWorkgroup < kMaxWorkgroups) {
    atomicAdd(groups_x, 1u);
  }
}
#endif

// --interpolation: the record receives w times its cell's average plus 1 - w times its own light, w of the slot's
// variance (core/cell_interpolation.cpp's SlotWeight: the channel sums and the square sum in their values).
dvec3 Interpolate(uint slot, ResolveParams p, dvec3 average, dvec3 own) {
  dvec3 channels;
  precise double square;
#ifdef HPSF_FIXED64
  for (uint c = 0u; c < 3u; ++c) channels[c] = double(sums[slot * 3u + c]) * p.unscale;
  square = double(uint64_t(square_words[2u * slot]) | (uint64_t(square_words[2u * slot + 1u]) << 32)) * square_unscale;
#else
  for (uint c = 0u; c < 3u; ++c) channels[c] = double(sums[slot * 3u + c]);
  square = double(uintBitsToFloat(square_words[slot]));
#endif
  double variance = SlotVariance(channels, square, double(SlotCount(slot)));
  double w = InterpolationWeight(interpolation_function, interpolation_v0, interpolation_v1, variance);
  return InterpolatedIncident(w, average, own);
}

void ResolvePixel(uint pixel, ResolveParams p) {
  precise dvec3 sum = dvec3(0.0LF);
#if defined(HPSF_DEFER_SEARCH)
  bool deferred = defer_every_pixel;  // then the pixel is the second pass's, which resolves all its records again
#endif
  for (uint s = 0u; s < p.samples_per_pixel; ++s) {
    uint i = pixel * p.samples_per_pixel + s;
    if (accepted[i] == 0u) continue;
    Record r = LoadShadingFields(i);
    precise dvec3 value = D(r.radiance_before);
    if (RecordHasVertex(r)) {
      LevelChoice chosen = ResolvedSlot(i, p);
      precise dvec3 incident = D(r.contribution);
      if (chosen.slot < p.capacity) {
#if defined(HPSF_DEFER_SEARCH)  // no early return: on a SIMD device the loop would carry each lane's exit
        if (p.neighbour_search != 0u && chosen.settled == 0u) deferred = true;
#endif
        HPSF_TOTAL_TYPE total = SlotSums(chosen.slot);
        uint64_t records_read = SlotCount(chosen.slot);
#if defined(HPSF_NEIGHBOUR_SEARCH)
        if (p.neighbour_search != 0u && chosen.settled == 0u) AddNeighbours(i, chosen, p, total, records_read);
#endif
        double count = double(records_read);
        for (int c = 0; c < 3; ++c) {
#ifdef HPSF_FIXED64
          precise double channel = double(total[c]) * p.unscale;
#elif defined(HPSF_PACKED_DECIMAL)  // sum / 1000, correctly rounded, as core/accumulation.h's IntegerSumValue
          precise double channel = double(total[c]) / double(kPackedDecimalScale);
#else
          precise double channel = total[c];
#endif
#if defined(HPSF_DEFECT_AVERAGE_OFF_BY_ONE)  // the slot's count taken as one more than it holds
          incident[c] = channel / (count + 1.0LF);
#elif defined(HPSF_DEFECT_AVERAGE_IN_FLOAT)  // the average in float32: other bits than core's double
          incident[c] = double(float(channel) / float(count));
#else
          incident[c] = channel / count;
#endif
        }
        // The host refuses the search with interpolation: the slot's own sums are the cell's.
        if (interpolation_function != kInterpolationOff) {
          dvec3 own = own_lights != 0u ? D(own_light[i]) : D(r.contribution);
          incident = Interpolate(chosen.slot, p, incident, own);
        }
      }
      value = value + D(r.throughput) * incident;
    }
    sum = sum + value;
  }
#if defined(HPSF_DEFER_SEARCH)
  if (deferred) {
    DeferPixel(pixel);
    return;
  }
#endif
  precise dvec3 mean = sum / double(p.samples_per_pixel);
  pixels[pixel * 3u] = float(mean.x);
  pixels[pixel * 3u + 1u] = float(mean.y);
  pixels[pixel * 3u + 2u] = float(mean.z);
}

#if defined(HPSF_SEARCH_DEFERRED_PIXELS)
void main() {
  ResolveParams p = params;
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint entry = gl_GlobalInvocationID.x; entry < deferred_count; entry += stride) {
    ResolvePixel(deferred_pixels[entry], p);
  }
}
#else
void main() {
  ResolveParams p = params;  // once per run: lavapipe gathers every push-constant read lane by lane
#if defined(HPSF_DEFER_SEARCH)
  defer_every_pixel = search.defer_every_pixel != 0u;
#endif
  SubgroupRuns runs = ThisSubgroupsRuns(kPixelsPerInvocation);
  for (uint first = runs.first; first < p.pixel_count; first += runs.stride) {
    uint end = min(first + runs.size, p.pixel_count);
    for (uint pixel = first + gl_SubgroupInvocationID; pixel < end; pixel += gl_SubgroupSize) ResolvePixel(pixel, p);
  }
}
#endif
