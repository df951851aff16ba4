#version 450
// The construction of a HashCache level's cuckoo map on the device (core/cuckoo_map.h holds the reference's, and
// emulated/cuckoo_kernels.h the emulator's): one invocation per key exchanges it into its first candidate with
// atomicExchange and carries the key it evicts on to that key's next candidate (core/shared/cuckoo.h), until a slot
// was empty or the chain passes its limit, where it counts a failure and the host rebuilds the map.
#extension GL_GOOGLE_include_directive : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/cuckoo.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Keys { uint keys[]; };
layout(std430, binding = 1) buffer Slots { uint slots[]; };
layout(std430, binding = 2) buffer Failed { uint failed; };
layout(push_constant) uniform Params {
  CuckooParams params;
  uint key_count;
  uint max_chain;
};

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < key_count; i += stride) {
    uint key = keys[i];
    uint slot = CuckooSlot(params, 0u, key);
    for (uint chain = 0u;; ++chain) {
      uint out_key = atomicExchange(slots[slot], key);
      if (out_key == kCuckooEmpty) break;
      if (chain == max_chain) {
        atomicAdd(failed, 1u);
        break;
      }
      key = out_key;
      slot = CuckooNextSlot(params, key, slot);
    }
  }
}
