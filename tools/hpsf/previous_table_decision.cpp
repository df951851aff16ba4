#include "tools/hpsf/previous_table_decision.h"

#include <numbers>

#include "core/footprint.h"

namespace hpsf {

std::optional<PreviousTableView> FramePreviousTableView(const FilterConfig& config, const TraceOptions& trace,
                                                        const PreparedScene& prepared, std::uint32_t index,
                                                        const FilterResult* exact, const HashTableDump* hashed) {
  const FrameEffects effects = PlanFrameEffects(config, index);
  if (!effects.survival && !effects.path_graph) return std::nullopt;
  // The key parameters the frame's records will be keyed with (the tracer's field of view, as the batch carries it).
  const double fov_y_radians = prepared.scene().camera.fov_y_degrees * std::numbers::pi / 180.0;
  const std::uint32_t records = trace.width * trace.height * trace.samples_per_pixel;
  const KeyParams params =
      MakeKeyParams(config, FootprintScale(config.filter_width_px, fov_y_radians, trace.height), records);
  if (exact) return PreviousTableView(config, params, *exact);
  if (hashed) return PreviousTableView(config, params, *hashed);
  return PreviousTableView(config, params);
}

}  // namespace hpsf
