#version 450
// The transport of several filtered bounces (core/transport.h; the step is core/shared/transport.h): one invocation
// per record, before the frame's accumulate. A record the host marked (it and its scattered vertex have vertices
// and passed the input checks) keys its scattered vertex with the key path of core/shared/key.h, looks the key up
// in the device table as the previous frame left it (no pass of this frame has written it yet, so no schedule
// changes what is read: D10's cousin cannot happen here), and adds the cell's average, carried back by the
// scattered vertex's throughput, to its own contribution. It writes the transported contribution and the slot it
// read, or kNothingTransported; the host judges both.
//
// Broken variants for the tests of a team's transport shader (--transport-spv): HPSF_DEFECT_WEIGHT_TWICE, the
// scattered vertex's throughput applied twice; HPSF_DEFECT_READ_PAST_THE_END, a found cell's slot written back one
// past the last slot.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "float_controls_fp64.glsl"
#include "../../core/shared/key.h"
#include "../../core/shared/lookup.h"
#include "../../core/shared/packed_sums.h"
#include "../../core/shared/probe_scheme.h"
#include "../../core/shared/table_params.h"
#include "../../core/shared/transport.h"

layout(local_size_x = 64) in;

// The scattered vertices, one per record of records then deeper, nine texels each (record_texels.glsl).
#define HPSF_RECORDS_BINDING 0
#include "record_texels.glsl"
layout(std430, binding = 1) readonly buffer Marked { uint marked[]; };  // 1: the record transports
// In: each record's contribution; out: where the record transports, its transported one.
layout(std430, binding = 2) buffer Contributions { vec4 contributions[]; };
// The table as the previous frame left it, read only: tags (slot_tags.glsl), sums and counts as the accumulate's.
layout(std430, binding = 3) readonly buffer Tags { uint tags[]; };
layout(std430, binding = 3) readonly buffer FullTags { uint64_t full_tags[]; };
layout(std430, binding = 4) readonly buffer SumWords { uint sum_words[]; };
layout(std430, binding = 5) readonly buffer Counts { uint64_t counts[]; };
layout(std430, binding = 5) readonly buffer CountWords { uint count_words[]; };  // packed-decimal's count words
layout(std430, binding = 6) writeonly buffer Read { uint read_slots[]; };  // the slot read, or kNothingTransported
layout(std430, binding = 7) buffer Stats { uint64_t unkeyable; };          // zeroed by the host
layout(push_constant) uniform Params {  // vulkan/transport_pass.cpp's TransportPush
  KeyParams key;
  double unscale;      // 2^-F, fixed64
  uint probe_limit;    // 0: no table before the frame, every lookup misses
  uint probe_scheme;   // kProbeLinear, kProbeBucket or kProbeBucketWindow
  uint accumulation;   // kAccumulateFixed64, kAccumulateFloat32 or kAccumulatePackedDecimal (table_params.h)
  uint reserved;
};

const uint kNothingTransported = 0xFFFFFFFFu;  // core/transport.h's

#define HPSF_TAGS_READONLY
#include "slot_tags.glsl"

uint64_t SlotCount(uint slot) {
  return accumulation == kAccumulatePackedDecimal ? uint64_t(PackedCount(count_words[slot])) : counts[slot];
}

// The slot holding the words' identity with samples, or kNothingTransported (core/level_seed.h's FindSlotInTable).
uint Find(KeyWords words, KeyParams k) {
  StoredIdentity identity = IdentityOfWords(words, k.key_identity, k.fingerprint_bits);
  if (!identity.fits) return kNothingTransported;
  uint slot0 = IndexHash(words, k.normal_in_index) & k.capacity_mask;
  uint64_t wanted = IdentityValue(identity.words);
  bool full = k.key_identity == kIdentityFull;
  ProbeScheme scheme = MakeProbeScheme(probe_scheme, k.capacity_mask + 1u, probe_limit);
  for (uint probe = 0u; probe < probe_limit; ++probe) {
    uint slot = CandidateSlot(scheme, slot0, probe);
    uint step = LookupStep(LoadTag(slot, full), wanted, SlotCount(slot));
    if (step == kLookupEnd) break;
    if (step == kLookupFound) return slot;
  }
  return kNothingTransported;
}

// The slot's average, sums / count per channel in double, as core/neighbour_search.h's StencilTotal of one cell.
dvec3 Average(uint slot) {
  precise double count = double(SlotCount(slot));
  dvec3 average;
  for (uint c = 0u; c < 3u; ++c) {
    uint w = slot * 3u + c;
    precise double sum;
    if (accumulation == kAccumulateFixed64) {
      sum = double(uint64_t(sum_words[2u * w]) | (uint64_t(sum_words[2u * w + 1u]) << 32)) * unscale;
    } else if (accumulation == kAccumulatePackedDecimal) {  // core/accumulation.h's IntegerSumValue
      sum = double(uint64_t(sum_words[w])) / double(kPackedDecimalScale);
    } else {
      sum = double(uintBitsToFloat(sum_words[w]));
    }
    average[c] = sum / count;
  }
  return average;
}

void Transport(uint i, KeyParams k) {
  read_slots[i] = kNothingTransported;
  if (marked[i] == 0u) return;
  Record s = LoadRecord(i);
  KeyResult scattered = ComputeKey(k, s);
  if (scattered.status == kKeyUnkeyable) {
    atomicAdd(unkeyable, 1ul);
    return;
  }
  uint slot = Find(scattered.words, k);
  if (slot == kNothingTransported) return;
#if defined(HPSF_DEFECT_WEIGHT_TWICE)
  s.throughput *= s.throughput;
#endif
  contributions[i] = vec4(TransportedContribution(contributions[i].xyz, s.throughput.xyz, Average(slot)), 0.0);
#if defined(HPSF_DEFECT_READ_PAST_THE_END)
  slot = k.capacity_mask + 1u;
#endif
  read_slots[i] = slot;
}

void main() {
  KeyParams k = key;  // once per run: lavapipe gathers every push-constant read lane by lane
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < k.record_count; i += stride) Transport(i, k);
}
