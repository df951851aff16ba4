// The deterministic path tracer: Embree 3 rays, cosine-sampled diffuse bounces, next-event estimation to the
// emitting triangles, Russian roulette for unbounded depth. It emits exactly one record per camera sample, in
// (pixel, sample) order: the filter vertex of docs/design/key-path.md or, without one, radiance_before.
// Every random number comes from the counter RNG and TBB splits the image into tiles whose samples are
// independent, so no output bit depends on the thread count.
#ifndef HPSF_TRACER_PATH_TRACER_H
#define HPSF_TRACER_PATH_TRACER_H

#include <cstdint>
#include <functional>
#include <memory>

#include "core/record.h"
#include "tracer/path_continuation.h"
#include "tracer/scene.h"

namespace hpsf {

// Bumped by every change that alters the records the tracer makes from the same scene and options: converged
// reference images (`hpsf reference`) are cached under it, so a new tracer never reads an old tracer's image.
inline constexpr int kTracerVersion = 1;
inline constexpr std::uint32_t kMaxFilteredVertices = 8;  // TraceOptions::filtered_vertices

struct TraceOptions {
  std::uint32_t width = 256;
  std::uint32_t height = 256;
  std::uint32_t samples_per_pixel = 4;
  std::uint32_t seed = 1;
  std::uint32_t frame = 0;  // in the counter RNG, and the time at which an animated scene is traced
  // Surface vertices per path, the series truncated after the last one's emission; -1: unbounded, ended by
  // Russian roulette.
  int max_depth = 8;
  std::uint32_t filter_bounce = 0;  // which diffuse vertex becomes the filter vertex; 0 is the primary hit
  // Several filtered bounces (core/transport.h): each path also records the vertex it scatters to from its filter
  // vertex (RecordBatch::scattered) and ends there, so the record holds the light of one vertex further (that
  // vertex's emission, no next-event estimate from it, as --max-depth truncates) and the transport takes what lies
  // beyond from the table.
  bool scattered = false;
  // With scattered: the vertices of each path filtered, the first at filter_bounce; the others are the batch's deeper
  // records (RecordBatch::deeper), each also with the vertex it scattered to. The path ends at the last one's.
  std::uint32_t filtered_vertices = 1;
  // Amortized (A-nHPSF, tracer/path_continuation.h), with scattered: 0 off; else each sample also extends the path it
  // kept from the frame before by one vertex, filtered as one more deeper record per sample, while that vertex's index
  // stays below this depth (Meijer's precedence rule: the deepest path still below it is kept).
  std::uint32_t continuation_depth = 0;
  int threads = 0;  // 0: all cores

  void Validate() const;  // ConfigError naming the option
};

struct TraceStats {
  std::uint64_t camera_rays = 0;
  std::uint64_t bounce_rays = 0;
  std::uint64_t shadow_rays = 0;
  std::uint64_t continued = 0;  // samples whose kept path grew by a vertex (continuation_depth)
  std::uint64_t Rays() const { return camera_rays + bounce_rays + shadow_rays; }
};

struct TraceResult {
  RecordBatch batch;
  TraceStats stats;
};

// A scene as it stands at one frame, built for tracing (its ray-tracing structure, emitters and normals). A static
// scene's is the same at every frame, so one serves a whole sequence; an animated scene's is built per frame
// (effect "animation", core/effect_plan.h).
class PreparedScene {
 public:
  PreparedScene(const Scene& scene, std::uint32_t frame);
  ~PreparedScene();
  PreparedScene(const PreparedScene&) = delete;
  PreparedScene& operator=(const PreparedScene&) = delete;

  std::uint32_t frame() const { return frame_; }
  bool animated() const { return animated_; }
  // What the tracer sees of it (tracer/scene_digest.h): equal at every frame of a static scene.
  std::uint64_t digest() const { return digest_; }
  const Scene& scene() const;

  struct Built;

 private:
  friend TraceResult TraceRecords(const PreparedScene&, const TraceOptions&,
                                  const std::function<void(std::uint32_t, std::uint32_t)>&, PathContinuation*);
  std::uint32_t frame_;
  bool animated_;
  std::uint64_t digest_;
  std::unique_ptr<Built> built_;
};

// progress(done, total) is called now and then from the calling thread's view of finished tiles. continuation: with
// options.continuation_depth, the state the frame before left, updated for the next; null, every sample starts afresh.
TraceResult TraceRecords(const Scene& scene, const TraceOptions& options,
                         const std::function<void(std::uint32_t, std::uint32_t)>& progress = {},
                         PathContinuation* continuation = nullptr);
// Traces a prepared scene: any frame of a static one, only its own frame of an animated one (a logic_error
// otherwise). The same records as TraceRecords of the scene.
TraceResult TraceRecords(const PreparedScene& prepared, const TraceOptions& options,
                         const std::function<void(std::uint32_t, std::uint32_t)>& progress = {},
                         PathContinuation* continuation = nullptr);

}  // namespace hpsf

#endif  // HPSF_TRACER_PATH_TRACER_H
