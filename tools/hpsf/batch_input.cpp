#include "tools/hpsf/batch_input.h"

#include <filesystem>

#include "core/record_file.h"
#include "tools/hpsf/image_size.h"
#include "tracer/scene_file.h"

namespace hpsf {

RecordBatch LoadOrTraceBatch(const std::string& input, const std::string& size, TraceOptions& trace,
                             std::uint32_t seed) {
  if (std::filesystem::path(input).extension() == ".hpsfv") return ReadRecordFile(input);
  ParseSize(size, trace);
  trace.seed = seed;
  trace.Validate();
  return TraceRecords(LoadScene(input), trace).batch;
}

}  // namespace hpsf
