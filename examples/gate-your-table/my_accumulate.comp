#version 450
// Our accumulate shader, against hpsf's stable buffer interface: fixed64 sums, every eviction policy, every probing
// scheme (CandidateSlot walks the declared scheme's candidates).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#define HPSF_SUMS_TYPE uint64_t
#include "core/shared/prelude.h"
#include "vulkan/shaders/float_controls.glsl"
#include "core/shared/key.h"
#include "core/shared/fixed_point.h"
#include "core/shared/table_params.h"
#include "core/shared/eviction_priority.h"
#include "vulkan/shaders/table_interface.glsl"

layout(local_size_x = 128) in;

// The first candidate that holds the fingerprint or that this record claims empty; compare-and-swap,
// never a load then a store.
uint FindOrClaimEmpty(uint slot0, uint fingerprint, TableParams t) {
  for (uint probe = 0u; probe < t.probe_limit; ++probe) {
    uint slot = CandidateSlot(ProbeSchemeOf(t), slot0, probe);
    uint tag = tags[slot];
    if (tag == 0u) tag = atomicCompSwap(tags[slot], 0u, fingerprint);  // returns 0: this record claimed it
    if (tag == 0u || tag == fingerprint) return slot;
  }
  return kPlacementProbeFailure;
}

// Priority eviction (t.claim_tombstones 1): look for the cell up to the first empty slot, then claim the first
// empty or tombstone slot, or join the cell a record of it claimed meanwhile.
uint FindOrClaim(uint slot0, uint fingerprint, TableParams t) {
  for (uint probe = 0u; probe < t.probe_limit; ++probe) {
    uint slot = CandidateSlot(ProbeSchemeOf(t), slot0, probe);
    uint tag = tags[slot];
    if (tag == fingerprint) return slot;
    if (tag == 0u) break;
  }
  for (uint probe = 0u; probe < t.probe_limit; ++probe) {
    uint slot = CandidateSlot(ProbeSchemeOf(t), slot0, probe);
    uint tag = tags[slot];
    if (tag == 0u || tag == kTombstoneTag) {
      uint seen = atomicCompSwap(tags[slot], tag, fingerprint);
      tag = seen == tag ? fingerprint : seen;
    }
    if (tag == fingerprint) return slot;
  }
  return kPlacementProbeFailure;
}

// One record's sums (fixed64: rounded half to even at 2^F) and count, wraps counted, then its last-seen frame.
void AddRecord(uint slot, Record r, TableParams t) {
  for (uint c = 0u; c < 3u; ++c) {
    uint64_t add = ToFixedPoint(r.contribution[c], t.fixed_point_scale);
    uint64_t old = atomicAdd(sums[slot * 3u + c], add);
    if (old + add < old) atomicAdd(wraps, uint64_t(1));
  }
  if (atomicAdd(counts[slot], uint64_t(1)) == ~uint64_t(0)) atomicAdd(count_wraps, uint64_t(1));
  if (t.track_last_seen != 0u) last_seen[slot] = t.frame;
}

void AccumulateRecord(uint i, KeyParams p, TableParams t) {
  if (accepted[i] == 0u) {  // rejected on the host: never read its fields
    StoreKeyResult(i, EmptyKeyResult(kKeyNoVertex));
    placements[i] = kPlacementNotPlaced;
    return;
  }
  Record r = LoadRecord(i);
  KeyResult k = ComputeKey(p, r);
  StoreKeyResult(i, k);
  uint placement = kPlacementNotPlaced;
  if (k.status == kKeyed) {
    placement = t.claim_tombstones != 0u ? FindOrClaim(k.slot0, k.fingerprint, t)
                                          : FindOrClaimEmpty(k.slot0, k.fingerprint, t);
    if (placement != kPlacementProbeFailure) AddRecord(placement, r, t);
  }
  placements[i] = placement;
}

void main() {
  KeyParams p = params;
  TableParams t = table;
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < p.record_count; i += stride) AccumulateRecord(i, p, t);
}
