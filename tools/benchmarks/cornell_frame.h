// The batch the emulator and Vulkan benchmarks share: the Cornell box traced at 1920x1080, 1 spp, about ten
// records per cell as a real frame gives; traced once per process.
#ifndef HPSF_TOOLS_BENCHMARKS_CORNELL_FRAME_H
#define HPSF_TOOLS_BENCHMARKS_CORNELL_FRAME_H

#include <cstdint>

#include "core/record.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf {

inline constexpr std::uint32_t kFrameRecords = 1920 * 1080;

inline const RecordBatch& CornellFrame() {
  static const RecordBatch batch = [] {
    TraceOptions options;
    options.width = 1920;
    options.height = 1080;
    options.samples_per_pixel = 1;
    return TraceRecords(LoadScene("cornell"), options).batch;
  }();
  return batch;
}

}  // namespace hpsf

#endif  // HPSF_TOOLS_BENCHMARKS_CORNELL_FRAME_H
