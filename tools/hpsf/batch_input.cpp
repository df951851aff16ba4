#include "tools/hpsf/batch_input.h"

#include <filesystem>

#include "core/record_file.h"
#include "tools/hpsf/image_size.h"
#include "tracer/scene_file.h"

namespace hpsf {

namespace {

bool IsRecordFile(const std::string& input) { return std::filesystem::path(input).extension() == ".hpsfv"; }

}  // namespace

void ResolveTraceOptions(const std::string& input, const std::string& size, TraceOptions& trace, std::uint32_t seed) {
  if (IsRecordFile(input)) return;
  ParseSize(size, trace);
  trace.seed = seed;
  trace.Validate();
}

RecordBatch LoadOrTraceBatch(const std::string& input, const TraceOptions& trace) {
  if (IsRecordFile(input)) return ReadRecordFile(input);
  return TraceRecords(LoadScene(input), trace).batch;
}

}  // namespace hpsf
