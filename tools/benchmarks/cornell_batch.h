// The batch the reference-filter and baseline benchmarks share: the Cornell box at 256x256, 4 spp (262,144
// records), traced once per process; small enough for the single-threaded reference and the radius search.
#ifndef HPSF_TOOLS_BENCHMARKS_CORNELL_BATCH_H
#define HPSF_TOOLS_BENCHMARKS_CORNELL_BATCH_H

#include "core/record.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf {

inline const RecordBatch& CornellBatch() {
  static const RecordBatch batch = [] {
    TraceOptions options;
    options.width = options.height = 256;
    options.samples_per_pixel = 4;
    return TraceRecords(LoadScene("cornell"), options).batch;
  }();
  return batch;
}

}  // namespace hpsf

#endif  // HPSF_TOOLS_BENCHMARKS_CORNELL_BATCH_H
