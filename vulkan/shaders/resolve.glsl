// The resolve pass (docs/design/algorithm.md), a separate pass after accumulate, pixel by pixel, no atomics: each
// record's value is radiance_before + throughput * the average of its slot (sum / count), or its own
// contribution without a slot, or radiance_before alone without a vertex; the pixel is the mean of its
// records in sample order. In double, operation for operation as core/resolve.cpp, so that with the same table
// the image is the same bits. resolve_fixed64.comp, resolve_float32.comp and resolve_packed_decimal.comp define the
// sums type (and packed-decimal the count word's, HPSF_COUNT_TYPE uint). The test suite
// compiles it once more per defect (HPSF_DEFECT_AVERAGE_OFF_BY_ONE, HPSF_DEFECT_AVERAGE_IN_FLOAT,
// HPSF_DEFECT_LEVEL_WRONG_COUNT), run through
// --resolve-spv as a team's own resolve would be.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "float_controls_fp64.glsl"
#include "../../core/shared/record_layout.h"
#include "../../core/shared/table_params.h"
#include "../../core/shared/packed_sums.h"
#include "../../core/shared/levels.h"
#ifndef HPSF_COUNT_TYPE
#define HPSF_COUNT_TYPE uint64_t
#endif
#include "subgroup_runs.glsl"

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

struct ResolveParams {  // vulkan_filter.cpp's ResolvePush
  double unscale;  // 2^-F, fixed64
  uint capacity;
  uint pixel_count;
  uint samples_per_pixel;
  uint levels;     // the placements hold `levels` words per record, level-major (core/shared/levels.h)
  uint min_count;  // the resolve reads a record's finest level whose count reaches it, else its coarsest
  uint reserved;
};
layout(push_constant) uniform Params { ResolveParams params; };

dvec3 D(vec4 v) { return dvec3(double(v.x), double(v.y), double(v.z)); }

uint64_t SlotCount(uint slot) {
#ifdef HPSF_PACKED_DECIMAL
  return uint64_t(PackedCount(counts[slot]));
#else
  return uint64_t(counts[slot]);
#endif
}

// The slot record i reads: its finest placed level whose count reaches min_count (core/shared/levels.h).
uint ResolvedSlot(uint i, ResolveParams p) {
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
  return choice.slot;
}

void ResolvePixel(uint pixel, ResolveParams p) {
  precise dvec3 sum = dvec3(0.0LF);
  for (uint s = 0u; s < p.samples_per_pixel; ++s) {
    uint i = pixel * p.samples_per_pixel + s;
    if (accepted[i] == 0u) continue;
    Record r = LoadShadingFields(i);
    precise dvec3 value = D(r.radiance_before);
    if (RecordHasVertex(r)) {
      uint slot = ResolvedSlot(i, p);
      precise dvec3 incident = D(r.contribution);
      if (slot < p.capacity) {
#ifdef HPSF_PACKED_DECIMAL
        double count = double(PackedCount(counts[slot]));
#else
        double count = double(counts[slot]);
#endif
        for (int c = 0; c < 3; ++c) {
#ifdef HPSF_FIXED64
          precise double channel = double(sums[slot * 3u + uint(c)]) * p.unscale;
#elif defined(HPSF_PACKED_DECIMAL)  // sum / 1000, correctly rounded, as core/accumulation.h's IntegerSumValue
          precise double channel = double(sums[slot * 3u + uint(c)]) / double(kPackedDecimalScale);
#else
          precise double channel = double(sums[slot * 3u + uint(c)]);
#endif
#if defined(HPSF_DEFECT_AVERAGE_OFF_BY_ONE)  // the slot's count taken as one more than it holds
          incident[c] = channel / (count + 1.0LF);
#elif defined(HPSF_DEFECT_AVERAGE_IN_FLOAT)  // the average in float32: other bits than core's double
          incident[c] = double(float(channel) / float(count));
#else
          incident[c] = channel / count;
#endif
        }
      }
      value = value + D(r.throughput) * incident;
    }
    sum = sum + value;
  }
  precise dvec3 mean = sum / double(p.samples_per_pixel);
  pixels[pixel * 3u] = float(mean.x);
  pixels[pixel * 3u + 1u] = float(mean.y);
  pixels[pixel * 3u + 2u] = float(mean.z);
}

void main() {
  ResolveParams p = params;  // once per run: lavapipe gathers every push-constant read lane by lane
  SubgroupRuns runs = ThisSubgroupsRuns(kPixelsPerInvocation);
  for (uint first = runs.first; first < p.pixel_count; first += runs.stride) {
    uint end = min(first + runs.size, p.pixel_count);
    for (uint pixel = first + gl_SubgroupInvocationID; pixel < end; pixel += gl_SubgroupSize) ResolvePixel(pixel, p);
  }
}
