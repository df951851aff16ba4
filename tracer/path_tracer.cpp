#include "tracer/path_tracer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/global_control.h>

#include "core/error.h"
#include "core/octahedral.h"
#include "core/parallel_for.h"
#include "core/path_graph.h"
#include "core/shared/rng.h"
#include "core/survival.h"
#include "core/tangent_frame.h"
#include "tracer/embree_scene.h"
#include "tracer/scene_digest.h"

namespace hpsf {
namespace {

// RNG dimensions within one bounce; the bounce index separates vertices.
constexpr std::uint32_t kPixelU = 0, kPixelV = 1, kLightPick = 2, kLightU = 3, kLightV = 4, kBounceU = 5, kBounceV = 6,
                        kRoulette = 7;  // 8: survival's (SurvivalDraw, core/survival.h)
constexpr std::uint32_t kTile = 16;

// The image's tiles of kTile x kTile pixels, row by row.
std::uint32_t TileCount(const TraceOptions& options) {
  return ((options.width + kTile - 1) / kTile) * ((options.height + kTile - 1) / kTile);
}

// sample(pixel, s) for every pixel of tile `tile` and every sample of each, in (pixel, sample) order.
template <typename Sample>
void ForEachTileSample(const TraceOptions& options, std::size_t tile, Sample sample) {
  const std::uint32_t tiles_x = (options.width + kTile - 1) / kTile;
  const auto ty = std::uint32_t(tile / tiles_x), tx = std::uint32_t(tile % tiles_x);
  for (std::uint32_t y = ty * kTile; y < std::min(options.height, (ty + 1) * kTile); ++y) {
    for (std::uint32_t x = tx * kTile; x < std::min(options.width, (tx + 1) * kTile); ++x) {
      for (std::uint32_t s = 0; s < options.samples_per_pixel; ++s) sample(y * options.width + x, s);
    }
  }
}
constexpr int kRouletteStart = 4;

double MaxComponent(glm::dvec3 v) { return std::max({v.x, v.y, v.z}); }

}  // namespace

// Emitting triangles, picked in proportion to their area. Outside the anonymous namespace: PreparedScene holds one.
class EmitterSampler {
 public:
  explicit EmitterSampler(const Scene& scene) {
    for (std::uint32_t i = 0; i < scene.triangles.size(); ++i) {
      if (!scene.materials[scene.triangles[i].material].IsEmissive()) continue;
      const Triangle& t = scene.triangles[i];
      const double area =
          0.5 * glm::length(glm::cross(glm::dvec3(t.p1) - glm::dvec3(t.p0), glm::dvec3(t.p2) - glm::dvec3(t.p0)));
      if (!(area > 0.0)) continue;
      total_area_ += area;
      triangles_.push_back(i);
      cumulative_.push_back(total_area_);
    }
  }
  bool Empty() const { return triangles_.empty(); }
  double TotalArea() const { return total_area_; }
  std::uint32_t Pick(double u) const {
    const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), u * total_area_);
    return triangles_[std::min<std::size_t>(it - cumulative_.begin(), triangles_.size() - 1)];
  }

 private:
  std::vector<std::uint32_t> triangles_;
  std::vector<double> cumulative_;
  double total_area_ = 0.0;
};

namespace {

struct SurfacePoint {
  glm::dvec3 position;
  glm::dvec3 normal;  // unit, facing the incoming ray
  const Material* material;
};

}  // namespace

// What tracing needs of a scene at a frame, built once: its triangles' ray-tracing structure, its emitters and its
// unit normals.
struct PreparedScene::Built {
  explicit Built(Scene at_frame) : scene(std::move(at_frame)), embree(scene), emitters(scene), extent(scene.Extent()) {
    // Unit geometric normals once per triangle, not once per hit.
    normals.reserve(scene.triangles.size());
    for (const Triangle& t : scene.triangles) {
      const glm::dvec3 p0(t.p0);
      normals.push_back(glm::normalize(glm::cross(glm::dvec3(t.p1) - p0, glm::dvec3(t.p2) - p0)));
    }
  }
  Scene scene;
  EmbreeScene embree;
  EmitterSampler emitters;
  double extent;
  std::vector<glm::dvec3> normals;
};

namespace {

// Where a path's records beyond its pixel record go (options.scattered): the vertex the pixel record's path scattered
// to, and for each further filtered vertex its record and the vertex it scattered to (filtered_vertices - 1 each).
struct PathOutputs {
  Record* scattered = nullptr;
  Record* deeper = nullptr;
  Record* deeper_scattered = nullptr;
  // With continuation_depth: where the vertex the last filtered one scattered to is kept (invalid without one).
  ContinuationVertex* fresh = nullptr;
  // With a path graph: the pixel record's own light (RecordBatch::own_light); 0 where it has no vertex.
  glm::vec4* own_light = nullptr;
};

// The counter RNG's bounce word of a continued vertex: apart from every bounce a frame's own paths draw (at most 1024).
constexpr std::uint32_t kContinuationStreams = 1u << 16;

class Tracer {
 public:
  Tracer(const PreparedScene::Built& built, const TraceOptions& options, const PreviousTableView* table)
      : scene_(built.scene),
        options_(options),
        table_(table),
        embree_(built.embree),
        emitters_(built.emitters),
        normals_(built.normals),
        extent_(built.extent) {
    const Camera& c = scene_.camera;
    forward_ = glm::normalize(c.look_at - c.position);
    right_ = glm::normalize(glm::cross(forward_, c.up));
    up_ = glm::cross(right_, forward_);
    tan_half_fov_ = std::tan(c.fov_y_degrees * std::numbers::pi / 360.0);
  }

  // The pixel record; with options.scattered also `out`'s.
  Record TraceSample(std::uint32_t pixel, std::uint32_t sample, TraceStats& stats, const PathOutputs& out) const;

  // The HashCache's samples of one camera sample (TraceCacheSamples): appended to `out`.
  void TraceCacheSamples(std::uint32_t pixel, std::uint32_t sample, const CacheSampling& sampling, TraceStats& stats,
                         std::vector<HashCacheSample>& out) const;

  // A-nHPSF: extends the sample's kept path by one vertex. Writes the kept vertex's record (its next-event estimate
  // and the next vertex's emission) and the vertex it scattered to, or records without a vertex where nothing is
  // kept; `kept` becomes the next vertex where the path goes on below continuation_depth, else invalid.
  void Continue(std::uint32_t pixel, std::uint32_t sample, ContinuationVertex& kept, TraceStats& stats, Record& deeper,
                Record& scattered) const;

 private:
  // The random numbers of one path vertex: the counter's prefix is hashed once, each dimension then finishes it.
  struct VertexRandom {
    std::uint32_t prefix;
    float operator()(std::uint32_t dimension) const { return shared::RandomFloatFromPrefix(prefix, dimension); }
  };
  VertexRandom RandomAt(std::uint32_t pixel, std::uint32_t sample, std::uint32_t bounce) const {
    return {shared::RngPrefix(shared::RngCounter{options_.seed, options_.frame, pixel, sample, bounce})};
  }

  // Rays leave a surface from a point pushed along the normal by a few float spacings of the scene's largest
  // coordinate, so they do not hit the surface they start on, however far from the origin the scene is.
  glm::dvec3 Offset(const SurfacePoint& p) const {
    const double spacing = std::ldexp(1.0, std::ilogb(std::max({MaxAbs(p.position), extent_ * 1e-3, 1e-30})) - 23);
    return p.position + p.normal * (32.0 * spacing);
  }

  // A cosine-weighted direction about p's normal, from the vertex's bounce dimensions.
  static glm::dvec3 CosineDirection(const SurfacePoint& p, const VertexRandom& random) {
    const TangentFrame frame = DuffTangentFrame(glm::vec3(p.normal));
    const double r = std::sqrt(double(random(kBounceU)));
    const double phi = 2.0 * std::numbers::pi * random(kBounceV);
    const double z = std::sqrt(std::max(0.0, 1.0 - r * r));
    return glm::normalize(glm::dvec3(frame.tangent) * (r * std::cos(phi)) +
                          glm::dvec3(frame.bitangent) * (r * std::sin(phi)) + p.normal * z);
  }

  // The camera ray of a sample: from the camera through the pixel, jittered by the sample's first two dimensions.
  glm::dvec3 CameraDirection(std::uint32_t pixel, std::uint32_t sample) const {
    const double px = pixel % options_.width, py = pixel / options_.width;
    const double aspect = double(options_.width) / double(options_.height);
    const VertexRandom camera_random = RandomAt(pixel, sample, 0);
    const double sx = (2.0 * (px + camera_random(kPixelU)) / options_.width - 1.0) * tan_half_fov_ * aspect;
    const double sy = (1.0 - 2.0 * (py + camera_random(kPixelV)) / options_.height) * tan_half_fov_;
    return glm::normalize(forward_ + right_ * sx + up_ * sy);
  }

  // A kept path's vertex as a record's vertex, keyed as the frame's own vertices are.
  static VertexSample KeptSample(std::uint32_t pixel, std::uint32_t sample, const ContinuationVertex& kept) {
    VertexSample v;
    v.pixel = pixel;
    v.sample = sample;
    v.bounce = kept.bounce;
    v.position = glm::vec3(kept.position);
    v.normal = glm::vec3(kept.normal);
    v.previous = glm::vec3(kept.previous);
    v.d_prefix = static_cast<float>(kept.d_prefix);
    return v;
  }

  std::optional<SurfacePoint> Cast(glm::dvec3 origin, glm::dvec3 direction) const {
    const auto hit = embree_.Intersect(glm::vec3(origin), glm::vec3(direction), 0.0f, INFINITY);
    if (!hit) return std::nullopt;
    const Triangle& t = scene_.triangles[hit->triangle];
    const glm::dvec3 p0(t.p0), p1(t.p1), p2(t.p2);
    SurfacePoint s;
    s.position = p0 * (1.0 - double(hit->u) - double(hit->v)) + p1 * double(hit->u) + p2 * double(hit->v);
    s.normal = normals_[hit->triangle];
    if (glm::dot(s.normal, direction) > 0.0) s.normal = -s.normal;
    s.material = &scene_.materials[t.material];
    return s;
  }

  // Incident radiance from the emitters at p, times cos / pi (the diffuse lobe without albedo): one sample.
  glm::dvec3 DirectLight(const SurfacePoint& p, const VertexRandom& random, TraceStats& stats) const {
    if (emitters_.Empty()) return glm::dvec3(0.0);
    const std::uint32_t light_index = emitters_.Pick(random(kLightPick));
    const Triangle& light = scene_.triangles[light_index];
    const double su = random(kLightU), sv = random(kLightV);
    const double root = std::sqrt(su);
    const glm::dvec3 y = glm::dvec3(light.p0) * (1.0 - root) + glm::dvec3(light.p1) * (root * (1.0 - sv)) +
                         glm::dvec3(light.p2) * (root * sv);
    const glm::dvec3 origin = Offset(p);
    const glm::dvec3 to_light = y - origin;
    const double distance = glm::length(to_light);
    if (!(distance > 0.0)) return glm::dvec3(0.0);
    const glm::dvec3 wi = to_light / distance;
    const double cos_surface = glm::dot(p.normal, wi);
    const glm::dvec3& light_normal = normals_[light_index];
    const double cos_light = std::abs(glm::dot(light_normal, wi));  // emission is two-sided
    if (cos_surface <= 0.0 || cos_light <= 0.0) return glm::dvec3(0.0);
    ++stats.shadow_rays;
    const double margin = 64.0 * std::ldexp(1.0, std::ilogb(std::max({MaxAbs(y), extent_ * 1e-3, 1e-30})) - 23);
    if (distance <= margin ||
        embree_.Occluded(glm::vec3(origin), glm::vec3(wi), 0.0f, static_cast<float>(distance - margin))) {
      return glm::dvec3(0.0);
    }
    const double geometry = cos_surface * cos_light / (distance * distance);
    const double light_pdf = distance * distance / (cos_light * emitters_.TotalArea());  // per solid angle
    const double mis = PowerHeuristic(light_pdf, cos_surface / std::numbers::pi);
    return glm::dvec3(scene_.materials[light.material].emission) *
           (mis * geometry * emitters_.TotalArea() / std::numbers::pi);
  }

  // The weight of emission found by a cosine-sampled bounce from `from` that hit the emitter point `p`: the
  // other half of multiple importance sampling with the next-event estimate above.
  double BounceEmissionWeight(const SurfacePoint& from, const SurfacePoint& p, glm::dvec3 direction) const {
    const double distance = glm::length(p.position - from.position);
    const double cos_light = std::abs(glm::dot(p.normal, direction));
    if (!(cos_light > 0.0) || emitters_.Empty()) return 1.0;
    const double light_pdf = distance * distance / (cos_light * emitters_.TotalArea());
    return PowerHeuristic(glm::dot(from.normal, direction) / std::numbers::pi, light_pdf);
  }

  static double PowerHeuristic(double pdf, double other_pdf) {
    const double a = pdf * pdf, b = other_pdf * other_pdf;
    return a + b > 0.0 ? a / (a + b) : 0.0;
  }

  const Scene& scene_;
  const TraceOptions& options_;
  // The table before the frame, for --survival (each path's survival at its primary vertex, core/survival.h) and
  // --path-graph (where each path is cut, core/path_graph.h); null where neither reads it.
  const PreviousTableView* table_;
  const EmbreeScene& embree_;
  const EmitterSampler& emitters_;
  const std::vector<glm::dvec3>& normals_;
  double extent_;
  glm::dvec3 forward_, right_, up_;
  double tan_half_fov_;
};

Record Tracer::TraceSample(std::uint32_t pixel, std::uint32_t sample, TraceStats& stats, const PathOutputs& out) const {
  glm::dvec3 origin = scene_.camera.position;
  glm::dvec3 direction = CameraDirection(pixel, sample);
  ++stats.camera_rays;

  // Before the filter vertex, `weight` is the camera-to-vertex throughput including albedos and `gathered` is
  // radiance_before (emission found at the filter vertex included); after it, `weight` restarts at 1 without the filter
  // vertex's albedo and `gathered` sums the contribution. Nothing is ever divided by an albedo. With several filtered
  // vertices (options_.scattered), each restarts them again: a filtered vertex's record holds the light of one vertex
  // further, and the vertex after it is the one it scattered to.
  const std::uint32_t filtered = options_.scattered ? options_.filtered_vertices : 1u;
  const std::uint32_t first = options_.filter_bounce;
  glm::dvec3 weight(1.0), gathered(0.0);
  glm::dvec3 radiance_before(0.0), record_throughput(0.0);
  std::array<VertexSample, kMaxFilteredVertices> chain, scattered_to;  // [j]: filtered vertex j, and its next vertex
  std::array<bool, kMaxFilteredVertices> has_scattered{};
  std::uint32_t reached = 0;  // filtered vertices the path reached
  glm::dvec3 previous = origin;
  std::optional<SurfacePoint> last;  // the previous surface vertex, for the weight of emission a bounce finds
  double d_prefix = 0.0;
  double survival = 1.0;       // the path's probability of surviving its primary vertex
  float survival_draw = 0.0f;  // and the draw that decided it
  const bool surviving = table_ && table_->survival().enabled();
  // Path graphs: the variance the path has gathered from its vertices' cells, and whether a cell has cut it. The cut
  // changes the record's own light only: own = before + cell + alpha (gathered - before), where `before` is what the
  // record gathered before the cut vertex and `cell` the cut cell's share. Its contribution, which its cell adds, is
  // the path's in full, so the table learns from traced light and not from its own averages.
  const bool graph = table_ && table_->path_graph().enabled;
  double graph_variance = 0.0;
  bool graph_cut = false;
  double graph_alpha = 1.0;
  glm::dvec3 graph_before(0.0), graph_cell(0.0);
  std::uint32_t max_vertices = options_.max_depth < 0 ? UINT32_MAX : std::uint32_t(options_.max_depth);
  if (options_.scattered) max_vertices = std::min(max_vertices, first + filtered + 1u);

  for (std::uint32_t bounce = 0; bounce < max_vertices; ++bounce) {
    const auto hit = Cast(origin, direction);
    if (!hit) {
      gathered += weight * glm::dvec3(scene_.sky);
      break;
    }
    const SurfacePoint& p = *hit;
    const glm::dvec3 albedo(p.material->albedo);
    const VertexRandom random = RandomAt(pixel, sample, bounce);
    // Emission the camera sees counts in full; emission a bounce finds shares the work with next-event
    // estimation through multiple importance sampling.
    if (p.material->IsEmissive()) {
      const double mis = bounce == 0 ? 1.0 : BounceEmissionWeight(*last, p, direction);
      gathered += weight * glm::dvec3(p.material->emission) * mis;
    }
    const double segment = MaxAbs(p.position - previous);
    // With a depth limit, a path is the series truncated after its last vertex's emission: that vertex's
    // next-event estimate is light from one vertex further, whose bounce-found half is never traced, so it
    // is not taken at all (taking it under its MIS weight adds a fraction of the next term).
    const bool last_vertex = bounce + 1 >= max_vertices;
    const auto here = [&](glm::dvec3 throughput) {
      VertexSample v;
      v.pixel = pixel;
      v.sample = sample;
      v.bounce = bounce;
      v.position = glm::vec3(p.position);
      v.normal = glm::vec3(p.normal);
      v.previous = glm::vec3(previous);
      v.d_prefix = static_cast<float>(d_prefix);
      v.throughput = glm::vec3(throughput);
      return v;
    };
    // Survival (core/survival.h), before any ray leaves the primary vertex: a culled path's record holds its vertex
    // and no light; a surviving one's light is divided by p at the end.
    if (surviving && bounce == first) {
      survival = table_->Probability(MakeVertexRecord(here(weight * albedo)));
      survival_draw = SurvivalDraw(options_.seed, options_.frame, pixel, sample, bounce);
      if (survival_draw >= survival) {
        ++stats.culled;
        radiance_before = gathered;
        record_throughput = weight * albedo;
        chain[0] = here(record_throughput);
        reached = 1;
        gathered = glm::dvec3(0.0);
        break;
      }
    }
    // Path graphs (core/path_graph.h), before any light is gathered at the vertex: its cell may cut the path. The cell
    // holds the light arriving at the vertex without its albedo, so its weight is the throughput from the filter
    // vertex up to and with the vertex's albedo (1 at the filter vertex, whose record holds that light itself).
    if (graph && !graph_cut && bounce >= first) {
      const glm::dvec3 tp = bounce == first ? glm::dvec3(1.0) : weight * albedo;
      if (const std::optional<CellEstimate> cell = table_->Cell(MakeVertexRecord(here(tp)))) {
        const double mean_tp = (tp.x + tp.y + tp.z) / 3.0;
        const PathGraphStep step =
            StepPathGraph(table_->path_graph(), graph_variance, mean_tp * mean_tp * cell->moments.variance);
        graph_variance = step.variance;
        if (step.cut) {
          graph_cut = true;
          ++stats.cut;
          graph_alpha = step.alpha;
          graph_cell = tp * cell->average * (1.0 - step.alpha);
          graph_before = bounce == first ? glm::dvec3(0.0) : gathered;  // the filter vertex restarts the record's light
        }
      }
    }
    const glm::dvec3 direct = last_vertex ? glm::dvec3(0.0) : DirectLight(p, random, stats);

    if (bounce >= first && bounce - first < filtered) {
      const std::uint32_t j = bounce - first;
      if (j == 0) {
        radiance_before = gathered;
        record_throughput = weight * albedo;
      } else {  // the previous filtered vertex's record is complete, and this is the vertex it scattered to
        chain[j - 1].contribution = glm::vec3(gathered);
        scattered_to[j - 1] = here(weight * albedo);
        has_scattered[j - 1] = true;
      }
      chain[j] = here(j == 0 ? record_throughput : weight * albedo);
      reached = j + 1;
      weight = glm::dvec3(1.0);
      gathered = direct;
    } else {
      weight *= albedo;
      gathered += weight * direct;
      if (options_.scattered && reached == filtered && !has_scattered[filtered - 1]) {  // the last one's next vertex
        scattered_to[filtered - 1] = here(weight);
        has_scattered[filtered - 1] = true;
        if (out.fresh) {
          *out.fresh = ContinuationVertex{true,       bounce,   std::uint32_t(p.material - scene_.materials.data()),
                                          p.position, p.normal, previous,
                                          d_prefix};
        }
      }
    }
    d_prefix += segment;
    previous = p.position;
    last = p;

    if (options_.max_depth < 0 && bounce + 1 >= kRouletteStart) {
      const double survive = std::min(0.95, MaxComponent(reached > 0 ? weight * record_throughput : weight));
      if (survive <= 0.0 || random(kRoulette) >= survive) break;
      weight /= survive;
    }
    if (last_vertex) break;

    // Cosine-weighted bounce: cos / pdf cancels the 1 / pi of the lobe, leaving the albedo (applied above).
    direction = CosineDirection(p, random);
    origin = Offset(p);
    ++stats.bounce_rays;
  }
  if (graph) stats.graph_variance_max = std::max(stats.graph_variance_max, graph_variance);
  if (reached > 0) {
    const auto decided = [&](const glm::dvec3& light) {
      return surviving ? SurvivingContribution(table_->survival(), light, survival_draw, survival) : glm::vec3(light);
    };
    chain[reached - 1].contribution = decided(gathered);
    if (out.own_light) {
      const glm::dvec3 own = graph_cut ? graph_before + graph_cell + graph_alpha * (gathered - graph_before) : gathered;
      *out.own_light = glm::vec4(decided(own), 0.0f);
    }
  }

  if (out.scattered) {
    const Record none = MakeRecordWithoutVertex(pixel, sample, glm::vec3(0.0f));
    for (std::uint32_t j = 0; j < filtered; ++j) {
      (j == 0 ? out.scattered[0] : out.deeper_scattered[j - 1]) =
          has_scattered[j] ? MakeVertexRecord(scattered_to[j]) : none;
      if (j > 0) out.deeper[j - 1] = j < reached ? MakeVertexRecord(chain[j]) : none;
    }
  }
  if (reached == 0) return MakeRecordWithoutVertex(pixel, sample, glm::vec3(gathered));
  chain[0].radiance_before = glm::vec3(radiance_before);
  return MakeVertexRecord(chain[0]);
}

void Tracer::TraceCacheSamples(std::uint32_t pixel, std::uint32_t sample, const CacheSampling& sampling,
                               TraceStats& stats, std::vector<HashCacheSample>& out) const {
  glm::dvec3 origin = scene_.camera.position;
  glm::dvec3 direction = CameraDirection(pixel, sample);
  ++stats.camera_rays;
  // Stored vertex i: where it is, its normal (facing the ray that found it), the light it has gathered, and the
  // throughput from it to the current vertex (the albedos after it; 1 at itself).
  std::array<SurfacePoint, kMaxCacheStore> stored;
  std::array<glm::dvec3, kMaxCacheStore> light, weight;
  std::uint32_t count = 0;
  std::optional<SurfacePoint> last;
  const std::uint32_t vertices = sampling.store + sampling.length;
  // Adds `radiance` arriving from vertex `from` (the emission found there, or a next-event estimate of it) to every
  // stored vertex within `length` vertices before it.
  const auto arrives = [&](std::uint32_t from, const glm::dvec3& radiance) {
    for (std::uint32_t i = 0; i < count; ++i) {
      if (i < from && from - i <= sampling.length) light[i] += weight[i] * radiance;
    }
  };
  for (std::uint32_t bounce = 0; bounce < vertices; ++bounce) {
    const auto hit = Cast(origin, direction);
    if (!hit) {
      arrives(bounce, glm::dvec3(scene_.sky));
      break;
    }
    const SurfacePoint& p = *hit;
    const VertexRandom random = RandomAt(pixel, sample, bounce);
    if (p.material->IsEmissive() && bounce > 0) {
      arrives(bounce, glm::dvec3(p.material->emission) * BounceEmissionWeight(*last, p, direction));
    }
    for (std::uint32_t i = 0; i < count; ++i) weight[i] *= glm::dvec3(p.material->albedo);
    if (bounce < sampling.store) {
      stored[count] = p;
      light[count] = glm::dvec3(0.0);
      weight[count] = glm::dvec3(1.0);
      ++count;
    }
    const bool last_vertex = bounce + 1 >= vertices;
    if (last_vertex) break;
    arrives(bounce + 1, DirectLight(p, random, stats));  // the emission of the next vertex, estimated
    last = p;
    direction = CosineDirection(p, random);
    origin = Offset(p);
    ++stats.bounce_rays;
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    HashCacheSample s;
    s.position = glm::vec3(stored[i].position);
    s.normal = PackOctahedral16(glm::vec3(stored[i].normal));
    s.light = glm::vec3(light[i]);
    out.push_back(s);
  }
}

void Tracer::Continue(std::uint32_t pixel, std::uint32_t sample, ContinuationVertex& kept, TraceStats& stats,
                      Record& deeper, Record& scattered) const {
  const Record none = MakeRecordWithoutVertex(pixel, sample, glm::vec3(0.0f));
  deeper = scattered = none;
  if (!kept.valid) return;
  ++stats.continued;
  const SurfacePoint p{kept.position, kept.normal, &scene_.materials[kept.material]};
  const VertexRandom random = RandomAt(pixel, sample, kContinuationStreams + kept.bounce);
  glm::dvec3 gathered = DirectLight(p, random, stats);
  const glm::dvec3 direction = CosineDirection(p, random);
  ++stats.bounce_rays;
  const auto hit = Cast(Offset(p), direction);
  if (hit && hit->material->IsEmissive()) {
    gathered += glm::dvec3(hit->material->emission) * BounceEmissionWeight(p, *hit, direction);
  } else if (!hit) {
    gathered += glm::dvec3(scene_.sky);
  }
  VertexSample v = KeptSample(pixel, sample, kept);
  v.contribution = glm::vec3(gathered);
  deeper = MakeVertexRecord(v);
  if (!hit) {
    kept.valid = false;
    return;
  }
  // The vertex it scattered to, keyed as any, with the transport weight of a cosine-sampled bounce: its albedo.
  const ContinuationVertex next{
      true,        kept.bounce + 1, std::uint32_t(hit->material - scene_.materials.data()), hit->position,
      hit->normal, kept.position,   kept.d_prefix + MaxAbs(kept.position - kept.previous)};
  VertexSample s = KeptSample(pixel, sample, next);
  s.throughput = hit->material->albedo;
  scattered = MakeVertexRecord(s);
  kept = next;
  kept.valid = next.bounce < options_.continuation_depth;
}

}  // namespace

PreparedScene::PreparedScene(const Scene& scene, std::uint32_t frame)
    : frame_(frame),
      animated_(!scene.animation.Static()),
      digest_(SceneDigest(scene, frame)),
      built_(std::make_unique<Built>(scene.AtFrame(frame))) {}

PreparedScene::~PreparedScene() = default;

const Scene& PreparedScene::scene() const { return built_->scene; }

TraceResult TraceRecords(const Scene& animated, const TraceOptions& options,
                         const std::function<void(std::uint32_t, std::uint32_t)>& progress,
                         PathContinuation* continuation, const PreviousTableView* table) {
  options.Validate();
  return TraceRecords(PreparedScene(animated, options.frame), options, progress, continuation, table);
}

TraceResult TraceRecords(const PreparedScene& prepared, const TraceOptions& options,
                         const std::function<void(std::uint32_t, std::uint32_t)>& progress,
                         PathContinuation* continuation, const PreviousTableView* table) {
  options.Validate();
  if (table && (options.filter_bounce != 0 || options.scattered)) {
    throw ConfigError(table->survival().enabled() ? "--survival" : "--path-graph",
                      "decides at a path's primary vertex: it needs --filter-bounce 0 and one filtered "
                      "vertex, without scattered vertices");
  }
  if (prepared.animated() && prepared.frame() != options.frame) {
    throw std::logic_error("an animated scene prepared at frame " + std::to_string(prepared.frame()) +
                           " traced at frame " + std::to_string(options.frame));
  }
  const int threads = options.threads > 0 ? options.threads : int(tbb::info::default_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const Scene& scene = prepared.scene();
  const Tracer tracer(*prepared.built_, options, table);

  TraceResult result;
  RecordBatch& batch = result.batch;
  batch.width = options.width;
  batch.height = options.height;
  batch.samples_per_pixel = options.samples_per_pixel;
  batch.fov_y_radians = scene.camera.fov_y_degrees * std::numbers::pi / 180.0;
  batch.frame = options.frame;
  batch.records.resize(std::size_t(options.width) * options.height * options.samples_per_pixel);
  // Per sample, its filtered vertices past the first, then with continuation_depth the vertex its kept path reached.
  const bool continuing = options.continuation_depth > 0;
  const std::size_t n = batch.records.size();
  const std::size_t more = options.scattered ? options.filtered_vertices - 1u + (continuing ? 1u : 0u) : 0u;
  if (options.scattered) {  // the records' scattered vertices, then the deeper records' (record i's at n + i more)
    batch.deeper.resize(n * more);
    batch.scattered.resize(n + n * more);
  }
  const bool graph = table && table->path_graph().enabled;
  if (graph) batch.own_light.assign(n, glm::vec4(0.0f));
  // The kept paths: the frame before's where they continue into this frame, else none.
  PathContinuation fresh_state;
  PathContinuation& state = continuation ? *continuation : fresh_state;
  std::vector<ContinuationVertex>* kept = nullptr;
  if (continuing) {
    const bool continues = state.ContinuesInto(options.frame, prepared.digest(), options.seed, n);
    kept = &state.Write(options.frame, prepared.digest(), options.seed, n);
    if (!continues) std::fill(kept->begin(), kept->end(), ContinuationVertex{});
  }

  const std::uint32_t tiles = TileCount(options);
  std::atomic<std::uint32_t> tiles_done{0};
  std::mutex stats_mutex;
  // One tile per task; the tiles' order does not change a record (each is a function of its pixel and sample).
  ParallelFor(
      tiles, 1,
      [&](std::size_t begin, std::size_t end) {
        TraceStats local;
        for (std::size_t tile = begin; tile < end; ++tile) {
          ForEachTileSample(options, tile, [&](std::uint32_t pixel, std::uint32_t s) {
            const std::size_t i = std::size_t(pixel) * options.samples_per_pixel + s;
            ContinuationVertex fresh;
            PathOutputs out = options.scattered
                                  ? PathOutputs{&batch.scattered[i], batch.deeper.data() + i * more,
                                                batch.scattered.data() + n + i * more, continuing ? &fresh : nullptr}
                                  : PathOutputs{};
            if (graph) out.own_light = &batch.own_light[i];
            batch.records[i] = tracer.TraceSample(pixel, s, local, out);
            if (continuing) {
              // The kept path grows by a vertex; where it cannot go on, the frame's own path is kept.
              ContinuationVertex& path = (*kept)[i];
              tracer.Continue(pixel, s, path, local, batch.deeper[i * more + more - 1],
                              batch.scattered[n + i * more + more - 1]);
              if (!path.valid && fresh.valid && fresh.bounce < options.continuation_depth) path = fresh;
            }
          });
          ++tiles_done;
        }
        std::lock_guard lock(stats_mutex);
        result.stats += local;
        if (progress) progress(tiles_done.load(), tiles);
      },
      threads);
  return result;
}

CacheTraceResult TraceCacheSamples(const PreparedScene& prepared, const TraceOptions& options,
                                   const CacheSampling& sampling) {
  options.Validate();
  sampling.Validate();
  if (prepared.animated() && prepared.frame() != options.frame) {
    throw std::logic_error("an animated scene prepared at frame " + std::to_string(prepared.frame()) +
                           " traced at frame " + std::to_string(options.frame));
  }
  const int threads = options.threads > 0 ? options.threads : int(tbb::info::default_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const Tracer tracer(*prepared.built_, options, nullptr);
  // Each tile's samples apart, joined in tile order: a tile's samples are a function of its pixels alone.
  std::vector<std::vector<HashCacheSample>> per_tile(TileCount(options));
  CacheTraceResult result;
  std::mutex stats_mutex;
  ParallelFor(
      per_tile.size(), 1,
      [&](std::size_t begin, std::size_t end) {
        TraceStats local;
        for (std::size_t tile = begin; tile < end; ++tile) {
          ForEachTileSample(options, tile, [&](std::uint32_t pixel, std::uint32_t s) {
            tracer.TraceCacheSamples(pixel, s, sampling, local, per_tile[tile]);
          });
        }
        std::lock_guard lock(stats_mutex);
        result.stats += local;
      },
      threads);
  for (const std::vector<HashCacheSample>& tile : per_tile) {
    result.samples.insert(result.samples.end(), tile.begin(), tile.end());
  }
  return result;
}

}  // namespace hpsf
