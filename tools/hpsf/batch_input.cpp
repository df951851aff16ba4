#include "tools/hpsf/batch_input.h"

#include <filesystem>
#include <optional>

#include "core/error.h"
#include "core/record_file.h"
#include "reference/reference_filter.h"
#include "tools/hpsf/effect_report.h"
#include "tools/hpsf/image_size.h"
#include "tools/hpsf/previous_table_decision.h"
#include "tracer/scene_file.h"

namespace hpsf {

bool IsRecordFile(const std::string& input) { return std::filesystem::path(input).extension() == ".hpsfv"; }

void ResolveTraceOptions(const std::string& input, const std::string& size, TraceOptions& trace, std::uint32_t seed) {
  if (IsRecordFile(input)) return;
  ParseSize(size, trace);
  trace.seed = seed;
  trace.Validate();
}

void CheckTransportInput(const std::string& input, std::span<const RecordBatch> frames, const FilterConfig& config) {
  if (!config.transport) return;
  for (const RecordBatch& batch : frames) {
    if (!batch.scattered.empty()) return;
  }
  throw ConfigError("--transport", input +
                                       ": no frame carries scattered vertices, so nothing would be transported "
                                       "(record the frames with --transport on, or filter without it)");
}

RecordBatch LoadOrTraceBatch(const std::string& input, const TraceOptions& trace) {
  if (IsRecordFile(input)) return ReadRecordFile(input);
  return TraceRecords(LoadScene(input), trace).batch;
}

std::vector<RecordBatch> LoadOrTraceFrames(const std::string& input, const TraceOptions& trace, std::uint32_t frames,
                                           const FilterConfig& config) {
  if (IsRecordFile(input)) return ReadRecordFrames(input);
  const Scene scene = LoadScene(input);
  std::vector<RecordBatch> sequence;
  TraceOptions frame_trace = trace;
  // A static scene is built once for every frame, an animated one for each (core/effect_plan.h, "animation").
  std::optional<PreparedScene> prepared;
  PathContinuation continuation;  // A-nHPSF's kept paths, from frame to frame
  // Survival and path graphs (core/previous_table_view.h) decide by the reference's exact map of the frame before, so
  // that every backend is handed the same records: the reference filters each frame once here, before the next is
  // traced.
  std::optional<FilterResult> decided;
  FilterConfig frame_config = config;
  for (std::uint32_t k = 0; k < frames; ++k) {
    frame_trace.frame = trace.frame + k;
    frame_config.frame = frame_trace.frame;
    if (!prepared || RebuildsScenePerFrame(config, FactsOf(scene))) {
      prepared.reset();
      prepared.emplace(scene, frame_trace.frame);
    }
    const std::optional<PreviousTableView> table_before =
        config.TracerReadsTable()
            ? FramePreviousTableView(frame_config, frame_trace, *prepared, k, decided ? &*decided : nullptr, nullptr)
            : std::nullopt;
    sequence.push_back(
        TraceRecords(*prepared, frame_trace, {}, &continuation, table_before ? &*table_before : nullptr).batch);
    if (config.TracerReadsTable() && k + 1 < frames) {
      decided = ReferenceFilter(sequence.back(), frame_config, decided ? &*decided : nullptr);
    }
  }
  return sequence;
}

}  // namespace hpsf
