// `hpsf render`'s loop over a traced sequence on one backend, each frame's adaptive decisions (survival, path graphs)
// read from the table that backend left the frame before: the reference's exact map or a hashed backend's own table.
#ifndef HPSF_PROPERTY_TESTS_OWN_TABLE_FRAMES_H
#define HPSF_PROPERTY_TESTS_OWN_TABLE_FRAMES_H

#include <cstdint>
#include <functional>
#include <optional>

#include "core/backend.h"
#include "core/filter_config.h"
#include "core/footprint.h"
#include "core/image.h"
#include "core/previous_table_view.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf::testing {

struct OwnTableFrames {
  Image image;               // the last frame's
  std::uint64_t culled = 0;  // over the frames: paths survival culled
  std::uint64_t cut = 0;     // and paths a path graph cut
};

// config.frames frames of `scene`, frame k traced by trace(k).
inline OwnTableFrames FilterDecidingByOwnTable(Backend& backend, const Scene& scene, const FilterConfig& config,
                                               const std::function<TraceOptions(std::uint32_t)>& trace) {
  OwnTableFrames run;
  const double fov = scene.camera.fov_y_degrees * 3.14159265358979323846 / 180.0;
  for (std::uint32_t k = 0; k < config.frames; ++k) {
    FilterConfig frame = config;
    frame.frame = k;
    const TraceOptions options = trace(k);
    const KeyParams params = MakeKeyParams(frame, FootprintScale(frame.filter_width_px, fov, options.height),
                                           options.width * options.height * options.samples_per_pixel);
    std::optional<PreviousTableView> view;
    if (k > 0 && backend.LastExactResult()) {
      view.emplace(frame, params, *backend.LastExactResult());
    } else if (k > 0) {
      view.emplace(frame, params, backend.LastHashedRun()->table);
    }
    const TraceResult traced = TraceRecords(scene, options, {}, nullptr, view ? &*view : nullptr);
    run.culled += traced.stats.culled;
    run.cut += traced.stats.cut;
    run.image = backend.FilterFrame(traced.batch, frame);
  }
  return run;
}

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_OWN_TABLE_FRAMES_H
