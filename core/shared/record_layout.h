// One sample record as the GPU sees it (std430: nine 16-byte vectors, 144 bytes) and as the host stores it,
// so a batch uploads with one copy. docs/design/key-path.md defines the fields.
#ifndef HPSF_CORE_SHARED_RECORD_LAYOUT_H
#define HPSF_CORE_SHARED_RECORD_LAYOUT_H

#include "prelude.h"

HPSF_SHARED_BEGIN

// path.z holds flags in its low 16 bits and the bounce of the filter vertex in its high 16 bits.
const uint kRecordHasVertex = 1u;
const uint kRecordFlagMask = 0xFFFFu;
const uint kRecordBounceShift = 16u;

struct Record {
  vec4 position;         // xyz: the filter vertex x; w: d_prefix, the L-infinity path length before x_prev
  vec4 normal;           // xyz: unit normal facing the incoming ray; w: 0
  vec4 tangent;          // xyz: T of the Duff et al. frame of the normal; w: 0
  vec4 bitangent;        // xyz: B; w: 0
  vec4 previous;         // xyz: x_prev, the previous path vertex (the camera for primary hits); w: 0
  vec4 contribution;     // rgb: incident radiance x cosine x diffuse lobe, without albedo; a: 0
  vec4 throughput;       // rgb: camera to vertex, times the albedo at the vertex; a: 0
  vec4 radiance_before;  // rgb: everything the path gathered before the vertex, unfiltered; a: 0
  uvec4 path;            // x: pixel, y: sample, z: flags | bounce << 16, w: octahedral normal u16 | v16 << 16
};

HPSF_FN uint RecordPixel(Record r) { return r.path.x; }
HPSF_FN uint RecordSample(Record r) { return r.path.y; }
HPSF_FN uint RecordBounce(Record r) { return r.path.z >> kRecordBounceShift; }
HPSF_FN bool RecordHasVertex(Record r) { return (r.path.z & kRecordHasVertex) != 0u; }

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_RECORD_LAYOUT_H
