// The deterministic path tracer: Embree 3 rays, cosine-sampled diffuse bounces, next-event estimation to the
// emitting triangles, Russian roulette for unbounded depth. It emits exactly one record per camera sample, in
// (pixel, sample) order: the filter vertex of docs/design/key-path.md or, without one, radiance_before.
// Every random number comes from the counter RNG and TBB splits the image into tiles whose samples are
// independent, so no output bit depends on the thread count.
#ifndef HPSF_TRACER_PATH_TRACER_H
#define HPSF_TRACER_PATH_TRACER_H

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>

#include "core/hashcache.h"
#include "core/previous_table_view.h"
#include "core/record.h"
#include "tracer/cache_sampling.h"
#include "tracer/path_continuation.h"
#include "tracer/scene.h"
#include "tracer/trace_options.h"

namespace hpsf {

// Bumped by every change that alters the records the tracer makes from the same scene and options: converged
// reference images (`hpsf reference`) are cached under it, so a new tracer never reads an old tracer's image.
inline constexpr int kTracerVersion = 1;

struct TraceStats {
  std::uint64_t camera_rays = 0;
  std::uint64_t bounce_rays = 0;
  std::uint64_t shadow_rays = 0;
  std::uint64_t continued = 0;  // samples whose kept path grew by a vertex (continuation_depth)
  std::uint64_t culled = 0;     // paths that did not survive their primary vertex (--survival)
  std::uint64_t cut = 0;        // paths a cell cut (--path-graph)
  // The most variance a path gathered from its cells (--path-graph): the bound at most.
  double graph_variance_max = 0.0;
  std::uint64_t Rays() const { return camera_rays + bounce_rays + shadow_rays; }
  // Another tile's: the counts summed, the largest variance kept.
  TraceStats& operator+=(const TraceStats& other) {
    camera_rays += other.camera_rays;
    bounce_rays += other.bounce_rays;
    shadow_rays += other.shadow_rays;
    continued += other.continued;
    culled += other.culled;
    cut += other.cut;
    graph_variance_max = std::max(graph_variance_max, other.graph_variance_max);
    return *this;
  }
};

struct TraceResult {
  RecordBatch batch;
  TraceStats stats;
};

struct CacheTraceResult {
  std::vector<HashCacheSample> samples;
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
                                  const std::function<void(std::uint32_t, std::uint32_t)>&, PathContinuation*,
                                  const PreviousTableView*);
  friend CacheTraceResult TraceCacheSamples(const PreparedScene&, const TraceOptions&, const CacheSampling&);
  std::uint32_t frame_;
  bool animated_;
  std::uint64_t digest_;
  std::unique_ptr<Built> built_;
};

// progress(done, total) is called now and then from the calling thread's view of finished tiles. continuation: with
// options.continuation_depth, the state the frame before left, updated for the next; null, every sample starts afresh.
// table: the table before the frame. With survival, each path survives its primary vertex (filter bounce 0, one
// filtered vertex) with the view's probability (core/survival.h), drawn from the counter RNG; with path graphs, each
// path is cut where its cells' variance passes the bound (core/path_graph.h). Null: every path is traced in full.
TraceResult TraceRecords(const Scene& scene, const TraceOptions& options,
                         const std::function<void(std::uint32_t, std::uint32_t)>& progress = {},
                         PathContinuation* continuation = nullptr, const PreviousTableView* table = nullptr);
// Traces a prepared scene: any frame of a static one, only its own frame of an animated one (a logic_error
// otherwise). The same records as TraceRecords of the scene.
TraceResult TraceRecords(const PreparedScene& prepared, const TraceOptions& options,
                         const std::function<void(std::uint32_t, std::uint32_t)>& progress = {},
                         PathContinuation* continuation = nullptr, const PreviousTableView* table = nullptr);

// The HashCache's samples (tracer/cache_sampling.h): per camera sample, its path's first sampling.store vertices, each
// with the light of the sampling.length vertices after it, in (pixel, sample, vertex) order. The same paths as
// TraceRecords draws (the same random numbers per vertex), traced to store + length vertices whatever
// options.max_depth; options' filtered vertices, survival and path graphs do not apply.
CacheTraceResult TraceCacheSamples(const PreparedScene& prepared, const TraceOptions& options,
                                   const CacheSampling& sampling);

}  // namespace hpsf

#endif  // HPSF_TRACER_PATH_TRACER_H
