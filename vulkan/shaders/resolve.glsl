// The resolve pass of DESIGN.md, a separate pass after accumulate, one invocation per pixel, no atomics: each
// record's value is radiance_before + throughput * the average of its slot (sum / count), or its own
// contribution without a slot, or radiance_before alone without a vertex; the pixel is the mean of its
// records in sample order. In double, operation for operation as core/resolve.cpp, so that with the same table
// the image is the same bits. resolve_fixed64.comp and resolve_float32.comp define the sums type.
#extension GL_GOOGLE_include_directive : require
#include "../../core/shared/prelude.h"
#include "float_controls.glsl"
#include "float_controls_fp64.glsl"
#include "../../core/shared/record_layout.h"
#include "../../core/shared/table_params.h"

#define HPSF_RECORDS_BINDING 0
#include "record_texels.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 1) readonly buffer Sums { HPSF_SUMS_TYPE sums[]; };
layout(std430, binding = 2) readonly buffer Counts { uint64_t counts[]; };
layout(std430, binding = 3) readonly buffer Placements { uint placements[]; };
layout(std430, binding = 4) readonly buffer Accepted { uint accepted[]; };
layout(std430, binding = 5) writeonly buffer Pixels { float pixels[]; };  // RGB per pixel
layout(push_constant) uniform Params {
  double unscale;  // 2^-F, fixed64
  uint capacity;
  uint pixel_count;
  uint samples_per_pixel;
  uint reserved;
};

dvec3 D(vec4 v) { return dvec3(double(v.x), double(v.y), double(v.z)); }

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint pixel = gl_GlobalInvocationID.x; pixel < pixel_count; pixel += stride) {
    precise dvec3 sum = dvec3(0.0LF);
    for (uint s = 0u; s < samples_per_pixel; ++s) {
      uint i = pixel * samples_per_pixel + s;
      if (accepted[i] == 0u) continue;
      Record r = LoadShadingFields(i);
      precise dvec3 value = D(r.radiance_before);
      if (RecordHasVertex(r)) {
        uint slot = placements[i];
        precise dvec3 incident = D(r.contribution);
        if (slot < capacity) {
          double count = double(counts[slot]);
          for (int c = 0; c < 3; ++c) {
#ifdef HPSF_FIXED64
            precise double channel = double(sums[slot * 3u + uint(c)]) * unscale;
#else
            precise double channel = double(sums[slot * 3u + uint(c)]);
#endif
            incident[c] = channel / count;
          }
        }
        value = value + D(r.throughput) * incident;
      }
      sum = sum + value;
    }
    precise dvec3 mean = sum / double(samples_per_pixel);
    pixels[pixel * 3u] = float(mean.x);
    pixels[pixel * 3u + 1u] = float(mean.y);
    pixels[pixel * 3u + 2u] = float(mean.z);
  }
}
