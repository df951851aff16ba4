#version 450
// The HashCache's occupancy on the device (core/occupancy.h is the reference's): one invocation per triangle rounds its
// vertices and tests every cell of its bounding box with core/shared/occupancy.h, setting the bits of the cells it meets
// by atomicOr, as Roth et al. rasterize triangles into their bit field (§3.1). A second dispatch counts the occupied
// cells: one popcount per word and one atomic add.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "../../core/shared/occupancy.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Triangles { vec4 vertices[]; };  // three per triangle, w unused
layout(std430, binding = 1) buffer Field { uint words[]; };
layout(std430, binding = 2) buffer Count { uint64_t occupied; };
layout(push_constant) uniform Params {
  int cell_exponent;
  int origin_x;
  int origin_y;
  int origin_z;
  int resolution_log2;
  int level;
  uint triangle_count;
  uint pass;  // 0: mark the triangles' cells; 1: count the field's words
};

void Mark(uint t) {
  OccupancyGrid g;
  g.cell_exponent = cell_exponent;
  g.origin_x = origin_x;
  g.origin_y = origin_y;
  g.origin_z = origin_z;
  g.resolution_log2 = resolution_log2;
  FixedPoint3 v0 = FixedVertex(g, vertices[3u * t].xyz);
  FixedPoint3 v1 = FixedVertex(g, vertices[3u * t + 1u].xyz);
  FixedPoint3 v2 = FixedVertex(g, vertices[3u * t + 2u].xyz);
  CellRange r = TriangleCellRange(v0, v1, v2, level, resolution_log2);
  int field_log2 = OccupancyFieldLog2(resolution_log2, level);
  for (int z = r.z0; z <= r.z1; ++z) {
    for (int y = r.y0; y <= r.y1; ++y) {
      for (int x = r.x0; x <= r.x1; ++x) {
        if (TriangleMeetsCell(v0, v1, v2, x, y, z, level)) {
          atomicOr(words[OccupancyWord(x, y, z, field_log2)], 1u << OccupancyBit(x, y, z));
        }
      }
    }
  }
}

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  if (pass == 0u) {
    for (uint t = gl_GlobalInvocationID.x; t < triangle_count; t += stride) Mark(t);
  } else {
    uint n = OccupancyWords(OccupancyFieldLog2(resolution_log2, level));
    for (uint w = gl_GlobalInvocationID.x; w < n; w += stride) {
      uint bits = uint(bitCount(words[w]));
      if (bits != 0u) atomicAdd(occupied, uint64_t(bits));
    }
  }
}
