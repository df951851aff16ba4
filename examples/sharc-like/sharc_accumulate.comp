#version 450
// A SHaRC-like cache's accumulate pass, written against hpsf's stable buffer interface as a team would write its own
// (examples/sharc-like/README.md): its own 64-bit key, stored whole in the slot (run with --key-source shader and
// --key-identity full), the declared probing scheme's candidates (buckets of 16 in sharc.json), and packed sums: each
// channel times 1000 added to a 32-bit word, the record count to the count word. hpsf's own passes then settle
// (halve) the words, evict stale cells (or, under hpsf fuzz, by priority) and keep the list of occupied slots.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#define HPSF_SUMS_TYPE uint
#define HPSF_COUNT_TYPE uint
#include "core/shared/prelude.h"
#include "vulkan/shaders/float_controls.glsl"
#include "core/shared/key.h"
#include "core/shared/eviction_priority.h"
#include "core/shared/fixed_point.h"
#include "core/shared/packed_sums.h"
#include "core/shared/table_params.h"
#include "vulkan/shaders/table_interface.glsl"

layout(local_size_x = 128) in;

// The grid (SHaRC's GridParameters, with logarithm base 2): at level L a voxel is 2^(L - kSharcLevelBias) / kSharcSceneScale
// wide, and a vertex's level grows with the log of its path length, so far voxels are larger. Both scales are powers
// of two, so the voxel of a position is exact.
const float kSharcSceneScale = 8.0;
const int kSharcLevelBias = 4;
const uint kSharcLevelMax = 1023u;            // 10 bits of level
const int kSharcCellLimit = 1 << 16;          // 17 bits per axis, two's complement
const uint kSharcAxisMask = 0x1FFFFu;

// The key of a record's vertex: its voxel (x, y, z), level and normal's octant, packed as SHaRC packs them, the level
// (at least 1) keeping the key from the empty tag 0. Words of one voxel give one identity and one home slot.
KeyResult SharcKey(Record r, uint capacity_mask) {
  KeyResult k = EmptyKeyResult(kKeyed);
  // The L-infinity path length to the vertex; its exponent is floor(log2), exactly.
  vec3 segment = abs(r.position.xyz - r.previous.xyz);
  float path_length = r.position.w + max(segment.x, max(segment.y, segment.z));
  int exponent = path_length > 0.0 ? int((floatBitsToUint(path_length) >> 23u) & 0xFFu) - 127 : 0;
  uint level = uint(clamp(exponent + kSharcLevelBias, 1, int(kSharcLevelMax)));
  vec3 grid = floor(ldexp(r.position.xyz * kSharcSceneScale, ivec3(kSharcLevelBias - int(level))));
  if (any(lessThan(grid, vec3(-kSharcCellLimit))) || any(greaterThanEqual(grid, vec3(kSharcCellLimit)))) {
    return EmptyKeyResult(kKeyUnkeyable);  // beyond 17 bits: keeps its own contribution
  }
  ivec3 cell = ivec3(grid);
  uint octant = (r.normal.x < 0.0 ? 1u : 0u) | (r.normal.y < 0.0 ? 2u : 0u) | (r.normal.z < 0.0 ? 4u : 0u);
  k.words.cell_x = uint(cell.x);
  k.words.cell_y = uint(cell.y);
  k.words.cell_z = uint(cell.z);
  k.words.level = level;
  k.words.normal = octant;
  k.words.extra = 0u;
  k.level = int(level);
  uint64_t key = uint64_t(uint(cell.x) & kSharcAxisMask) | (uint64_t(uint(cell.y) & kSharcAxisMask) << 17) |
                 (uint64_t(uint(cell.z) & kSharcAxisMask) << 34) | (uint64_t(level) << 51) | (uint64_t(octant) << 61);
  k.fingerprint = uint(key);
  k.identity_high = uint(key >> 32);
  k.slot0 = Pcg(k.fingerprint ^ Pcg(k.identity_high)) & capacity_mask;  // the home slot: a hash of the whole key
  return k;
}

// The first candidate that holds the key or that this record claims, by a 64-bit compare-and-swap: an empty slot,
// or, with hpsf's priority eviction (claim_tombstones), a slot it evicted and tagged kTombstoneTag. A tombstone may lie
// before the key's own slot, so then the key is looked for first, up to the first empty slot.
uint FindOrClaim(uint slot0, uint64_t key, TableParams t) {
  const uint64_t tombstone = t.claim_tombstones != 0u ? uint64_t(kTombstoneTag) : 0ul;
  for (uint probe = 0u; tombstone != 0ul && probe < t.probe_limit; ++probe) {
    uint64_t tag = full_tags[CandidateSlot(ProbeSchemeOf(t), slot0, probe)];
    if (tag == key) return CandidateSlot(ProbeSchemeOf(t), slot0, probe);
    if (tag == 0ul) break;
  }
  for (uint probe = 0u; probe < t.probe_limit; ++probe) {
    uint slot = CandidateSlot(ProbeSchemeOf(t), slot0, probe);
    uint64_t tag = full_tags[slot];
    if (tag == 0ul || tag == tombstone) {
      uint64_t seen = atomicCompSwap(full_tags[slot], tag, key);  // returns tag: this record claimed it
      tag = seen == tag ? key : seen;
    }
    if (tag == key) return slot;
  }
  return kPlacementProbeFailure;
}

// One record's packed sums and count, wraps counted, then its last-seen frame (for hpsf's stale-frame eviction).
void AddRecord(uint slot, Record r, TableParams t) {
  for (uint c = 0u; c < 3u; ++c) {
    uint add = uint(ToFixedPoint(r.contribution[c], t.fixed_point_scale));  // the host checked it fits 32 bits
    uint old = atomicAdd(sums[slot * 3u + c], add);
    if (old + add < old) atomicAdd(wraps, uint64_t(1));
  }
  if ((atomicAdd(counts[slot], 1u) & kPackedCountMask) == kPackedCountMask) atomicAdd(count_wraps, uint64_t(1));
  if (t.track_last_seen != 0u) last_seen[slot] = t.frame;
}

void AccumulateRecord(uint i, KeyParams p, TableParams t) {
  if (accepted[i] == 0u) {  // rejected on the host: never read its fields
    StoreKeyResult(i, EmptyKeyResult(kKeyNoVertex));
    placements[i] = kPlacementNotPlaced;
    return;
  }
  Record r = LoadRecord(i);
  KeyResult k = RecordHasVertex(r) ? SharcKey(r, p.capacity_mask) : EmptyKeyResult(kKeyNoVertex);
  StoreKeyResult(i, k);
  uint placement = kPlacementNotPlaced;
  if (k.status == kKeyed) {
    placement = FindOrClaim(k.slot0, (uint64_t(k.identity_high) << 32) | uint64_t(k.fingerprint), t);
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
