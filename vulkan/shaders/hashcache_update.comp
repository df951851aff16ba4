#version 450
// The HashCache's frame update by sort and reduce on the device (core/hashcache_update.h holds the reference's and
// emulated/hashcache_update_kernels.h the emulator's), one stage a dispatch, level by level: the samples become the
// finest level's elements; each element locates its cell's slot and claims the cell's front with atomicCompSwap,
// then takes its side (core/shared/hashcache_cell.h); a bitonic sort of the order words, its steps of strides below
// 512 run in workgroup memory, one dispatch for all of them, the others one dispatch a step; and the reduce, where the
// head of each segment adds its segment in order, updates its cell's side once and appends its parent's element for
// the level above at a place an atomic counter hands out (the level above sorts them, so their places change no
// bit).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/cuckoo.h"
#include "../../core/shared/fixed_point.h"
#include "../../core/shared/hashcache_cell.h"

layout(local_size_x = 256) in;
const uint kLocalSortSpan = 512u;  // elements a workgroup sorts in its own memory: two per invocation

struct Sample {
  vec3 position;
  uint normal;
  vec3 light;
  uint unused;
};
// core's HashCacheElement: 64 bytes.
struct Element {
  uint key;
  uint side;
  uint origin;
  uint slot;
  uint64_t fixed_sums[3];
  uint64_t count;
  float light[3];
  uint unused;
};

layout(std430, binding = 0) readonly buffer Samples { Sample samples[]; };
layout(std430, binding = 1) readonly buffer Map { uint map_slots[]; };
layout(std430, binding = 2) buffer Fronts { uint fronts[]; };
layout(std430, binding = 3) buffer FixedSums { uint64_t fixed_sums[]; };
layout(std430, binding = 4) buffer FloatSums { float float_sums[]; };
layout(std430, binding = 5) buffer Counts { uint64_t counts[]; };
layout(std430, binding = 6) buffer In { Element elements[]; };
layout(std430, binding = 7) buffer Out { Element parents[]; };
layout(std430, binding = 8) buffer Orders { uint64_t orders[]; };
layout(std430, binding = 9) buffer Perm { uint perm[]; };
layout(std430, binding = 10) buffer Counters {
  uint missed;
  uint lost;
  uint appended;  // the parents' elements appended by this level's reduce
};
layout(push_constant) uniform Params {
  CuckooParams params;
  int cell_exponent;
  int origin_x;
  int origin_y;
  int origin_z;
  int resolution_log2;
  uint stage;  // 0: samples to elements; 1: locate and claim; 2: a sort step; 3: reduce; 4: reset the count of
               // appended parents; 5: the sort's steps of strides below kLocalSortSpan for one block size (or all
               // block sizes up to kLocalSortSpan where sort_block is 0), in workgroup memory; 6: the atomics rule's
               // update of the level by every sample
  int level;
  int cells_log2;
  uint positions;  // the sort's span: a power of two, at least kLocalSortSpan
  uint element_count;  // this level's elements (at the finest, the samples)
  uint sort_block;
  uint sort_stride;
  uint fixed64;
  float scale;
  uint defect;  // 1: the front claimed by a load and a store (HPSF_DEFECT-style variant of the emulator's)
};

const uint64_t kNoOrder = 0xFFFFFFFFFFFFFFFFul;

void SampleElement(uint i) {
  if (i >= element_count) return;
  OccupancyGrid g;
  g.cell_exponent = cell_exponent;
  g.origin_x = origin_x;
  g.origin_y = origin_y;
  g.origin_z = origin_z;
  g.resolution_log2 = resolution_log2;
  ivec3 cell = PointCell(g, samples[i].position);
  if (cell.x < 0) {
    atomicAdd(missed, 1u);
    elements[i].key = kCuckooEmpty;
    return;
  }
  elements[i].key = CuckooKey(cell.x, cell.y, cell.z, cells_log2);
  elements[i].side = FrontWord(samples[i].normal);
  elements[i].origin = i;
  for (uint c = 0u; c < 3u; ++c) {
    float light = Flush(samples[i].light[c]);
    elements[i].light[c] = light;
    elements[i].fixed_sums[c] = fixed64 != 0u ? ToFixedPoint(light, scale) : 0ul;
  }
  elements[i].count = 1ul;
}

void Locate(uint i) {
  perm[i] = i;
  uint key = i < element_count ? elements[i].key : kCuckooEmpty;
  if (key == kCuckooEmpty) {
    orders[i] = kNoOrder;
    return;
  }
  uint slot = kCuckooEmpty;
  for (uint f = 0u; f < params.functions && slot == kCuckooEmpty; ++f) {
    uint candidate = CuckooSlot(params, f, key);
    if (map_slots[candidate] == key) slot = candidate;
  }
  if (slot == kCuckooEmpty) {
    if (level == 0) {
      atomicAdd(missed, 1u);
    } else {
      atomicAdd(lost, 1u);
    }
    orders[i] = kNoOrder;
    return;
  }
  uint side = elements[i].side;
  uint front;
  if (defect == 1u) {
    front = fronts[slot];
    if (front == kFrontUnclaimed) {
      fronts[slot] = side;
      front = side;
    }
  } else {
    uint old = atomicCompSwap(fronts[slot], kFrontUnclaimed, side);
    front = old == kFrontUnclaimed ? side : old;
  }
  bool back = !FacesFront(side, front);
  elements[i].slot = slot;
  orders[i] = (uint64_t(SegmentWord(key, back)) << 32) | uint64_t(elements[i].origin);
}

// The atomics rule (core/hashcache.h): sample i locates its cell at the level, claims its front and adds its light to
// its side by atomic adds.
void AtomicUpdate(uint i) {
  if (i >= element_count) return;
  OccupancyGrid g;
  g.cell_exponent = cell_exponent;
  g.origin_x = origin_x;
  g.origin_y = origin_y;
  g.origin_z = origin_z;
  g.resolution_log2 = resolution_log2;
  ivec3 finest = PointCell(g, samples[i].position);
  if (finest.x < 0) {
    if (level == 0) atomicAdd(missed, 1u);
    return;
  }
  ivec3 cell = finest >> level;
  uint key = CuckooKey(cell.x, cell.y, cell.z, cells_log2);
  uint slot = kCuckooEmpty;
  for (uint f = 0u; f < params.functions && slot == kCuckooEmpty; ++f) {
    uint candidate = CuckooSlot(params, f, key);
    if (map_slots[candidate] == key) slot = candidate;
  }
  if (slot == kCuckooEmpty) {
    if (level == 0) atomicAdd(missed, 1u);
    return;
  }
  uint side = FrontWord(samples[i].normal);
  uint old = atomicCompSwap(fronts[slot], kFrontUnclaimed, side);
  uint front = old == kFrontUnclaimed ? side : old;
  uint back = FacesFront(side, front) ? 0u : 1u;
  for (uint c = 0u; c < 3u; ++c) {
    atomicAdd(fixed_sums[6u * slot + 3u * back + c], ToFixedPoint(Flush(samples[i].light[c]), scale));
  }
  atomicAdd(counts[2u * slot + back], 1ul);
}

void SortStep(uint t) {
  uint j = sort_stride;
  uint i = ((t & ~(j - 1u)) << 1u) | (t & (j - 1u));  // the pair (i, i + j): bit j of i is clear
  uint l = i + j;
  bool ascending = (i & sort_block) == 0u;
  uint64_t a = orders[i];
  uint64_t b = orders[l];
  if (ascending ? a <= b : a >= b) return;
  orders[i] = b;
  orders[l] = a;
  uint p = perm[i];
  perm[i] = perm[l];
  perm[l] = p;
}

void Reduce(uint i) {
  uint64_t order = orders[i];
  bool head = order != kNoOrder && (i == 0u || (orders[i - 1u] >> 32) != (order >> 32));
  if (!head) return;
  uint word = uint(order >> 32);
  uint first = perm[i];
  uint slot = elements[first].slot;
  uint64_t fixed_total[3] = uint64_t[3](0ul, 0ul, 0ul);
  precise float light_total[3] = float[3](0.0, 0.0, 0.0);
  uint64_t count = 0ul;
  for (uint at = i; at < positions; ++at) {
    if (at > i && (orders[at] >> 32) != uint64_t(word)) break;
    uint e = perm[at];
    for (uint c = 0u; c < 3u; ++c) {
      fixed_total[c] += elements[e].fixed_sums[c];
      light_total[c] = at == i ? elements[e].light[c] : light_total[c] + elements[e].light[c];
    }
    count += elements[e].count;
  }
  uint side = SegmentBack(word) ? 1u : 0u;
  for (uint c = 0u; c < 3u; ++c) {
    uint at = 6u * slot + 3u * side + c;
    if (fixed64 != 0u) {
      fixed_sums[at] += fixed_total[c];
    } else {
      precise float sum = float_sums[at] + light_total[c];
      float_sums[at] = sum;
    }
  }
  counts[2u * slot + side] += count;
  if (cells_log2 == 0) return;
  uint front = fronts[slot];
  uint at = atomicAdd(appended, 1u);
  parents[at].key = ParentKey(SegmentKey(word), cells_log2);
  parents[at].side = side != 0u ? NegatedFront(front) : front;
  parents[at].origin = word;
  for (uint c = 0u; c < 3u; ++c) {
    parents[at].fixed_sums[c] = fixed_total[c];
    parents[at].light[c] = light_total[c];
  }
  parents[at].count = count;
}

shared uint64_t local_orders[kLocalSortSpan];
shared uint local_perm[kLocalSortSpan];

// The compare-and-exchange of the pair (i, i + j) of the block, in workgroup memory; `base` the block's first position,
// so the direction is the whole sort's.
void LocalStep(uint base, uint t, uint k, uint j) {
  uint i = ((t & ~(j - 1u)) << 1u) | (t & (j - 1u));
  uint l = i + j;
  bool ascending = ((base + i) & k) == 0u;
  uint64_t a = local_orders[i];
  uint64_t b = local_orders[l];
  if (ascending ? a > b : a < b) {
    local_orders[i] = b;
    local_orders[l] = a;
    uint p = local_perm[i];
    local_perm[i] = local_perm[l];
    local_perm[l] = p;
  }
}

// Stage 5: every invocation of the workgroup runs every step (barriers in uniform control flow).
void LocalSort() {
  uint base = gl_WorkGroupID.x * kLocalSortSpan;
  uint t = gl_LocalInvocationID.x;
  local_orders[t] = orders[base + t];
  local_orders[t + 256u] = orders[base + t + 256u];
  local_perm[t] = perm[base + t];
  local_perm[t + 256u] = perm[base + t + 256u];
  barrier();
  uint k_first = sort_block == 0u ? 2u : sort_block;
  uint k_last = sort_block == 0u ? kLocalSortSpan : sort_block;
  for (uint k = k_first; k <= k_last; k <<= 1u) {
    for (uint j = min(k >> 1u, kLocalSortSpan >> 1u); j > 0u; j >>= 1u) {
      LocalStep(base, t, k, j);
      barrier();
    }
  }
  orders[base + t] = local_orders[t];
  orders[base + t + 256u] = local_orders[t + 256u];
  perm[base + t] = local_perm[t];
  perm[base + t + 256u] = local_perm[t + 256u];
}



void main() {
  if (stage == 5u) {
    LocalSort();
    return;
  }
  if (stage == 4u) {
    if (gl_GlobalInvocationID.x == 0u) appended = 0u;
    return;
  }
  uint items = stage == 2u ? positions >> 1u : positions;
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < items; i += stride) {
    if (stage == 0u) {
      SampleElement(i);
    } else if (stage == 1u) {
      Locate(i);
    } else if (stage == 2u) {
      SortStep(i);
    } else if (stage == 6u) {
      AtomicUpdate(i);
    } else {
      Reduce(i);
    }
  }
}
