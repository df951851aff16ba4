#include "tools/hpsf/sweep_command.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <tuple>

#include <nlohmann/json.hpp>

#include "core/footprint.h"
#include "core/hashed_run.h"
#include "reference/radius_search_filter.h"
#include "reference/reference_filter.h"
#include "reference/screen_space_filter.h"
#include "tools/hpsf/backend_options.h"
#include "tools/hpsf/bias_variance_plot.h"
#include "tools/hpsf/channel_image_file.h"
#include "tools/hpsf/filter_options.h"
#include "tools/hpsf/frame_soundness.h"
#include "tools/hpsf/frames_plot.h"
#include "tools/hpsf/heatmap.h"
#include "tools/hpsf/html_report.h"
#include "tools/hpsf/image_file.h"
#include "tools/hpsf/image_size.h"
#include "tools/hpsf/pareto_plot.h"
#include "tools/hpsf/previous_table_decision.h"
#include "tools/hpsf/reference_cache.h"
#include "tools/hpsf/seconds_since.h"
#include "tools/hpsf/sweep_grid.h"
#include "tools/hpsf/sweep_html_report.h"
#include "tracer/path_continuation.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "verifier/contract/hashcache_run.h"
#include "verifier/gate/gate_file.h"
#include "verifier/metrics/channel_image.h"
#include "verifier/metrics/error_split.h"
#include "verifier/metrics/fireflies.h"
#include "verifier/metrics/image_metrics.h"
#include "verifier/metrics/pareto.h"
#include "verifier/metrics/ssim.h"

namespace hpsf {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// The seed of the converged image: apart from the sweep's seeds 1..K, so that no image is measured against its own
// samples.
constexpr std::uint32_t kReferenceSeed = 1000003;

struct SweepOptions {
  std::string scene;
  std::string grid;
  std::string size = "128x128";
  std::uint32_t seeds = 3;
  std::uint32_t reference_spp = 1024;
  int max_depth = 8;
  std::string cache;
  std::string shard = "1/1";
  std::string out = "hpsf-sweep";
  bool json = false;
};

FilterConfig FilterConfigOf(const SweepConfig& c) {
  CLI::App app;
  FilterOptions options;
  AddFilterOptions(app, options);
  std::vector<std::string> words = {"sweep"};
  const std::vector<std::string> arguments = c.FilterArguments();
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<const char*> argv;
  for (const std::string& w : words) argv.push_back(w.c_str());
  try {
    app.parse(int(argv.size()), argv.data());
    return ResolveFilterConfig(options);
  } catch (const CLI::ParseError& e) {
    throw ConfigError("--grid", c.id + ": " + e.what());
  } catch (const InputError& e) {
    throw ConfigError("--grid", c.id + ": " + e.what());
  }
}

Image ColourOf(const ChannelImage& c, const std::string& prefix) {
  Image image(std::uint32_t(c.width), std::uint32_t(c.height));
  const int r = c.ChannelIndex(prefix + "R"), g = c.ChannelIndex(prefix + "G"), b = c.ChannelIndex(prefix + "B");
  if (r < 0 || g < 0 || b < 0) throw InputError(c.path + ": no " + prefix + "R, G, B channels");
  for (std::size_t p = 0; p < image.pixels.size(); ++p) {
    image.pixels[p] = glm::vec3(c.At(p, std::size_t(r)), c.At(p, std::size_t(g)), c.At(p, std::size_t(b)));
  }
  return image;
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// One traced frame: its batch, the tracer's time and rays.
struct TracedFrame {
  RecordBatch batch;
  double seconds = 0.0;
  std::uint64_t rays = 0;
};

// The scene built for tracing at a frame: a static scene's once for every frame, an animated one's per frame. Its
// build is in no configuration's time (a renderer builds a static scene once, not per frame).
class SceneAtFrame {
 public:
  explicit SceneAtFrame(const Scene& scene) : scene_(scene) {}
  const PreparedScene& At(std::uint32_t frame) {
    if (!prepared_ || (prepared_->animated() && prepared_->frame() != frame)) {
      prepared_.reset();
      prepared_.emplace(scene_, frame);
    }
    return *prepared_;
  }

 private:
  const Scene& scene_;
  std::optional<PreparedScene> prepared_;
};

TracedFrame TraceFrame(SceneAtFrame& scene, const TraceOptions& trace, PathContinuation& continuation,
                       const PreviousTableView* table_before = nullptr) {
  const auto start = Clock::now();
  TraceResult traced = TraceRecords(scene.At(trace.frame), trace, {}, &continuation, table_before);
  return {std::move(traced.batch), SecondsSince(start), traced.stats.Rays()};
}

// How a configuration's paths are traced: the sweep's options, the configuration's spp, and its method's and trace
// axes' choices. nhpsf and anhpsf trace the scattered vertices the transport reads; anhpsf keeps each sample's path
// to the continuation depth (by default the sweep's --max-depth, the converged image's).
TraceOptions TraceOf(const SweepConfig& c, const TraceOptions& sweep) {
  TraceOptions trace = sweep;
  trace.samples_per_pixel = c.spp;
  if (c.max_depth) trace.max_depth = *c.max_depth;
  if (c.Transports()) {
    trace.scattered = true;
    trace.filtered_vertices = c.filtered_vertices.value_or(1u);
    if (c.method == "anhpsf") {
      trace.continuation_depth =
          c.continuation_depth.value_or(sweep.max_depth < 0 ? 1024u : std::uint32_t(sweep.max_depth));
    }
  }
  try {
    trace.Validate();
  } catch (const ConfigError& e) {
    throw ConfigError("--grid", c.id + ": " + e.what());
  }
  return trace;
}

// The HashCache of a hashcache configuration, checked before anything runs: a ConfigError naming --grid.
HashCacheSettings HashCacheSettingsOf(const SweepConfig& c, const FilterConfig& config) {
  HashCacheSettings settings;
  settings.resolution_log2 = c.cache_resolution.value_or(7);
  settings.accumulation = config.accumulation;
  settings.frames = c.frames;
  if (c.cache_update == "atomics") settings.update = HashCacheUpdateRule::kAtomics;
  try {
    settings.Validate();
  } catch (const ConfigError& e) {
    throw ConfigError("--grid", c.id + ": " + e.what());
  }
  return settings;
}

// What a configuration traces, as a key: configurations of one frame that trace alike share their batches.
std::string TraceKey(const TraceOptions& t) {
  return std::to_string(t.samples_per_pixel) + "/" + std::to_string(t.max_depth) + "/" + std::to_string(t.scattered) +
         "/" + std::to_string(t.filtered_vertices) + "/" + std::to_string(t.continuation_depth);
}

// One seed of one configuration, over its frames: the image after the last, its relMSE after each, the medians over
// frames of the trace and filter times and the hashed backends' phases, the rays per pixel per frame, the table's
// probe failures (over every frame) and aliased slots (in the last frame's table).
struct SeedRun {
  Image image;
  std::vector<double> relmse_by_frame;
  double trace_s = 0.0, filter_s = 0.0, rays_per_pixel = 0.0;
  json phases = json::object();
  std::uint64_t probe_failures = 0, aliased_slots = 0;
  json hashcache;  // the HashCache's: its last reconstruction's fill, its constructions, the last update's misses
};

class Runner {
 public:
  explicit Runner(const Scene& scene) : scene_(scene) {}

  // A hashed method's frames go through one backend whose table carries over (its temporal mode is the
  // configuration's --temporal); every other method shows the mean of its frames' images, as a progressive renderer
  // does, or on an animated scene its last frame's (a mean over a moving scene would blur). A frame `cached`
  // (one-frame configurations) is used as traced; otherwise each frame is traced in turn. `references`: one converged
  // image for every frame (a static scene), or one per frame (an animated one).
  SeedRun Run(const SweepConfig& c, FilterConfig config, TraceOptions trace, std::uint32_t seed,
              const TracedFrame* cached, const std::vector<ChannelImage>& references) {
    if (c.method == "hashcache") return RunHashCache(c, config, trace, seed, references);
    SeedRun run;
    trace.seed = config.seed = seed;
    config.frames = c.frames;
    config.transport = c.Transports();
    if (c.survival) {  // survival reads each cell's variance
      config.survival = ParseSurvival(*c.survival);
      config.second_moments = true;
    }
    if (c.path_graph) {  // so do path graphs
      config.path_graph = ParsePathGraph(*c.path_graph);
      config.second_moments = true;
    }
    PathContinuation continuation;
    BackendInstance* backend = c.Hashed() ? &BackendFor(c.backend) : nullptr;
    if (backend) backend->backend->Reset();
    std::vector<double> trace_s, filter_s;
    std::map<std::string, std::vector<double>> phases;
    std::vector<glm::dvec3> sum;  // the other methods' frames, summed
    std::uint64_t rays = 0;
    for (std::uint32_t f = 0; f < c.frames; ++f) {
      trace.frame = config.frame = f;
      TracedFrame traced_now;
      if (!cached) {
        // Survival and path graphs read the table the frame before left in the configuration's backend.
        const HashedRun* hashed = f > 0 && backend ? backend->backend->LastHashedRun() : nullptr;
        const std::optional<PreviousTableView> table_before =
            config.TracerReadsTable() ? FramePreviousTableView(config, trace, scene_.At(f), f,
                                                               f > 0 ? backend->backend->LastExactResult() : nullptr,
                                                               hashed ? &hashed->table : nullptr)
                                      : std::nullopt;
        traced_now = TraceFrame(scene_, trace, continuation, table_before ? &*table_before : nullptr);
      }
      const TracedFrame& traced = cached ? *cached : traced_now;
      trace_s.push_back(traced.seconds);
      rays += traced.rays;
      const auto start = Clock::now();
      Image image;
      if (backend) {
        image = backend->backend->FilterFrame(traced.batch, config);
        filter_s.push_back(SecondsSince(start));
        RequireSoundFrame(*backend->backend, image, config);
        if (backend->info->hashed) {  // the reference times none of its phases
          const FrameTimings t = backend->backend->LastFrameTimings();
          if (t.keys_ms) phases["key_s"].push_back(*t.keys_ms / 1e3);  // Vulkan computes keys in its accumulate
          if (config.transport) phases["transport_s"].push_back(t.transport_ms / 1e3);
          if (config.temporal.blends()) phases["temporal_s"].push_back(t.temporal_ms / 1e3);
          if (config.eviction.enabled()) phases["eviction_s"].push_back(t.eviction_ms / 1e3);
          phases["accumulate_s"].push_back(t.accumulate_ms / 1e3);
          phases["resolve_s"].push_back(t.resolve_ms / 1e3);
          if (t.transfer_ms) phases["transfer_s"].push_back(*t.transfer_ms / 1e3);
        }
        if (const HashedRun* hashed = backend->backend->LastHashedRun()) {
          run.probe_failures += hashed->probe_failures;
          if (f + 1 == c.frames) {
            const std::vector<bool> aliased = AliasedSlots(*hashed);
            run.aliased_slots = std::uint64_t(std::count(aliased.begin(), aliased.end(), true));
          }
        }
      } else {
        const Image frame = c.method == "pt"       ? UnfilteredImage(traced.batch)
                            : c.method == "radius" ? RadiusSearchFilter(traced.batch, config).image
                                                   : ScreenSpaceFilter(traced.batch, config).image;
        sum.resize(frame.pixels.size(), glm::dvec3(0.0));
        image = Image(frame.width, frame.height);
        for (std::size_t p = 0; p < sum.size(); ++p) {
          sum[p] += glm::dvec3(frame.pixels[p]);
          image.pixels[p] = references.size() > 1 ? frame.pixels[p] : glm::vec3(sum[p] / double(f + 1));
        }
        filter_s.push_back(SecondsSince(start));
      }
      const ChannelImage& reference = references[std::min<std::size_t>(f, references.size() - 1)];
      run.relmse_by_frame.push_back(ComputeMetrics(ColourChannels(image), reference).relmse);
      if (f + 1 == c.frames) run.image = std::move(image);
    }
    run.trace_s = Median(trace_s);
    run.filter_s = Median(filter_s);
    run.rays_per_pixel = double(rays) / (double(trace.width) * trace.height * c.frames);
    for (const auto& [name, values] : phases) run.phases[name] = Median(values);
    return run;
  }

  // The HashCache (verifier/contract/hashcache_run.h) on the configuration's backend, over its frames: each frame
  // builds the cache where the geometry changed (its time is the build's own phase, in no frame's), traces the cache
  // samples and caches them (the trace and the update), traces the primary hits and reconstructs (the trace and the
  // reconstruction). The image is the last frame's: the cache integrates every frame. A problem the family's checker
  // finds in a construction or an update ends the sweep with a failed check.
  SeedRun RunHashCache(const SweepConfig& c, const FilterConfig& config, TraceOptions trace, std::uint32_t seed,
                       const std::vector<ChannelImage>& references) {
    SeedRun run;
    const BackendInfo& info = FindBackend(c.backend, "--grid");
    HashCacheSettings settings = HashCacheSettingsOf(c, config);
    settings.seed = seed;
    VulkanDevice* device = info.kind == BackendKind::kVulkan ? BackendFor(c.backend).device.get() : nullptr;
    HashCacheRun cache(info, settings, EmulatorOptions{}, device);
    const CacheSampling sampling{c.cache_store.value_or(3), c.cache_length.value_or(3)};
    trace.seed = seed;
    std::vector<double> trace_s, filter_s, build_s, update_s, reconstruct_s;
    std::uint64_t rays = 0;
    for (std::uint32_t f = 0; f < c.frames; ++f) {
      trace.frame = f;
      const PreparedScene& prepared = scene_.At(f);
      std::vector<OccupancyTriangle> triangles;
      for (const Triangle& t : prepared.scene().triangles) triangles.push_back({t.p0, t.p1, t.p2});
      if (cache.Prepare(triangles, "the sweep's scene")) {
        build_s.push_back((cache.timings().occupancy_ms + cache.timings().maps_ms) / 1e3);
      }
      auto start = Clock::now();
      const CacheTraceResult samples = TraceCacheSamples(prepared, trace, sampling);
      TraceOptions primary_trace = trace;
      primary_trace.max_depth = 1;  // the primary hits alone: what the camera sees is reconstructed from the cache
      TraceResult primary = TraceRecords(prepared, primary_trace);
      trace_s.push_back(SecondsSince(start));
      rays += samples.stats.Rays() + primary.stats.Rays();
      cache.Update(samples.samples);
      const HashCacheReconstruction reconstruction = cache.Reconstruct(
          primary.batch, FootprintScale(config.filter_width_px, primary.batch.fov_y_radians, trace.height),
          config.jitter_scale, f);
      if (!cache.problems().empty()) {
        throw CheckFailed(c.id + ", seed " + std::to_string(seed) + ": the HashCache's checker found " +
                          std::to_string(cache.problems().size()) + " problems; the first: " + cache.problems()[0]);
      }
      update_s.push_back(cache.timings().update_ms / 1e3);
      reconstruct_s.push_back(cache.timings().reconstruct_ms / 1e3);
      filter_s.push_back(update_s.back() + reconstruct_s.back());
      const ChannelImage& reference = references[std::min<std::size_t>(f, references.size() - 1)];
      run.relmse_by_frame.push_back(ComputeMetrics(ColourChannels(reconstruction.image), reference).relmse);
      if (f + 1 == c.frames) {
        run.image = reconstruction.image;
        run.hashcache = {{"filled_fraction", reconstruction.FilledFraction()},
                         {"unfilled", reconstruction.unfilled},
                         {"lookups", reconstruction.lookups},
                         {"builds", cache.timings().builds},
                         {"levels_unchanged_at_last_build", cache.timings().levels_unchanged},
                         {"missed_samples", cache.missed()}};
      }
    }
    run.trace_s = Median(trace_s);
    run.filter_s = Median(filter_s);
    run.rays_per_pixel = double(rays) / (double(trace.width) * trace.height * c.frames);
    run.phases["cache_update_s"] = Median(update_s);
    run.phases["reconstruct_s"] = Median(reconstruct_s);
    run.phases["cache_build_s"] = Median(build_s);
    return run;
  }

  // The one-frame batches of seeds 1..K traced with `trace`, kept for every configuration that traces alike.
  const std::vector<TracedFrame>& OneFrame(const TraceOptions& trace, std::uint32_t seeds) {
    const std::string key = TraceKey(trace);
    if (key != one_frame_key_) {
      one_frame_.clear();
      for (std::uint32_t k = 1; k <= seeds; ++k) {
        TraceOptions seeded = trace;
        seeded.seed = k;
        seeded.frame = 0;
        PathContinuation continuation;
        one_frame_.push_back(TraceFrame(scene_, seeded, continuation));
      }
      one_frame_key_ = key;
    }
    return one_frame_;
  }

 private:
  BackendInstance& BackendFor(const std::string& name) {
    auto it = backends_.find(name);
    if (it == backends_.end()) it = backends_.emplace(name, MakeBackend(name, EmulatorOptions{})).first;
    return it->second;
  }
  SceneAtFrame scene_;
  std::map<std::string, BackendInstance> backends_;
  std::string one_frame_key_;
  std::vector<TracedFrame> one_frame_;
};

// Everything a configuration's figures depend on: a kept result is reused only when this matches.
std::string Description(const SweepConfig& c, const SweepOptions& o, const std::string& reference) {
  return c.id + "; " + o.size + ", seeds 1.." + std::to_string(o.seeds) + ", max depth " + std::to_string(o.max_depth) +
         "; against " + reference;
}

std::string ConfigFile(const fs::path& out, std::size_t index, const SweepConfig& c) {
  std::string name = c.id;
  for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '.' ? ch : '_';
  char prefix[16];
  std::snprintf(prefix, sizeof prefix, "%04zu-", index);
  return (out / "configs" / (prefix + name + ".json")).string();
}

// The converged images a sweep measures against: one of frame 0 for a static scene; for an animated one, one per
// frame, each configuration measured against its last frame's.
struct Converged {
  ReferenceImage entry;
  Image image, variance;
  ChannelImage channels;
};

// `image_exr`: where the first seed's image goes (with its PNG preview beside it).
json MeasureConfig(const SweepConfig& c, const FilterConfig& config, const TraceOptions& trace, std::uint32_t seeds,
                   const std::vector<Converged>& converged, std::uint32_t reference_spp, Runner& runner,
                   const std::string& image_exr) {
  const Converged& last = converged[std::min<std::size_t>(c.frames - 1, converged.size() - 1)];
  const Image& reference = last.image;
  const Image& reference_variance = last.variance;
  const ChannelImage& reference_channels = last.channels;
  std::vector<ChannelImage> references;
  for (const Converged& frame : converged) references.push_back(frame.channels);
  const std::vector<TracedFrame>* one_frame = c.frames == 1 ? &runner.OneFrame(trace, seeds) : nullptr;
  std::vector<Image> images;
  std::vector<double> trace_s, filter_s, mse, relmse, ssim, fireflies, rays_per_pixel;
  std::vector<std::vector<double>> relmse_by_frame(c.frames);  // per frame, each seed's
  std::map<std::string, std::vector<double>> phases;
  std::uint64_t probe_failures = 0, aliased = 0;
  std::vector<json> hashcache_runs;
  for (std::uint32_t k = 1; k <= seeds; ++k) {
    SeedRun run = runner.Run(c, config, trace, k, one_frame ? &(*one_frame)[k - 1] : nullptr, references);
    const ChannelImage channels = ColourChannels(run.image);
    const ImageMetrics metrics = ComputeMetrics(channels, reference_channels);
    trace_s.push_back(run.trace_s);
    filter_s.push_back(run.filter_s);
    rays_per_pixel.push_back(run.rays_per_pixel);
    mse.push_back(metrics.mse);
    relmse.push_back(metrics.relmse);
    ssim.push_back(SrgbSsim(channels, reference_channels));
    // Against path tracing's spread at the samples a pixel holds after the frames.
    fireflies.push_back(
        double(CountFireflies(run.image, c.spp * c.frames, reference, reference_variance, reference_spp)));
    for (std::uint32_t f = 0; f < c.frames; ++f) relmse_by_frame[f].push_back(run.relmse_by_frame[f]);
    for (auto it = run.phases.begin(); it != run.phases.end(); ++it) phases[it.key()].push_back(it.value());
    probe_failures += run.probe_failures;
    aliased += run.aliased_slots;
    if (!run.hashcache.is_null()) hashcache_runs.push_back(run.hashcache);
    images.push_back(std::move(run.image));
  }
  WriteImageFiles(image_exr, images[0], {{"sweep_config", c.id}, {"seed", "1"}});
  const auto mean = [](const std::vector<double>& v) {
    double sum = 0.0;
    for (const double x : v) sum += x;
    return sum / double(v.size());
  };
  json result = {{"id", c.id},
                 {"method", c.method},
                 {"backend", c.backend},
                 {"spp", c.spp},
                 {"frames", c.frames},
                 {"trace",
                  {{"max_depth", trace.max_depth},
                   {"filtered_vertices", trace.filtered_vertices},
                   {"continuation_depth", trace.continuation_depth}}},
                 {"filter", json::object()},
                 {"seeds", seeds},
                 {"trace_s", Median(trace_s)},
                 {"filter_s", Median(filter_s)},
                 {"total_s", Median(trace_s) + Median(filter_s)},
                 {"rays_per_pixel", mean(rays_per_pixel)},
                 {"mse", mean(mse)},
                 {"relmse", mean(relmse)},
                 {"ssim", mean(ssim)},
                 {"fireflies", mean(fireflies)},
                 {"probe_failures", probe_failures},
                 {"aliased_slots", aliased}};
  if (c.frames > 1) {
    json by_frame = json::array();
    for (const std::vector<double>& seeds_relmse : relmse_by_frame) by_frame.push_back(mean(seeds_relmse));
    result["relmse_by_frame"] = by_frame;  // the last is the relMSE
  }
  // The trace axes the grid set for this method (the CSV's columns), beside "trace", which holds what was traced.
  json trace_axes = json::object();
  if (c.max_depth) trace_axes["max-depth"] = std::to_string(*c.max_depth);
  if (c.filtered_vertices) trace_axes["filtered-vertices"] = std::to_string(*c.filtered_vertices);
  if (c.continuation_depth) trace_axes["continuation-depth"] = std::to_string(*c.continuation_depth);
  if (c.survival) trace_axes["survival"] = *c.survival;
  if (c.path_graph) trace_axes["path-graph"] = *c.path_graph;
  if (c.cache_resolution) trace_axes["cache-resolution"] = std::to_string(*c.cache_resolution);
  if (c.cache_store) trace_axes["cache-store"] = std::to_string(*c.cache_store);
  if (c.cache_length) trace_axes["cache-length"] = std::to_string(*c.cache_length);
  if (c.cache_update) trace_axes["cache-update"] = *c.cache_update;
  result["trace_axes"] = trace_axes;
  if (!hashcache_runs.empty()) {
    std::vector<double> filled;
    for (const json& h : hashcache_runs) filled.push_back(h["filled_fraction"].get<double>());
    result["hashcache"] = hashcache_runs[0];
    result["hashcache"]["filled_fraction"] = mean(filled);  // over the seeds; the rest are the first seed's
  }
  for (const auto& [name, value] : c.filter) result["filter"][name] = value;
  for (const auto& [name, values] : phases) result["phases"][name] = Median(values);
  if (images.size() >= 2) {
    const ErrorSplit split = SplitError(images, reference, &reference_variance);
    result["bias2"] = split.bias2;
    result["bias2_standard_error"] = split.bias2_standard_error;
    result["mean_error"] = split.mean_error;
    result["mean_error_standard_error"] = split.mean_error_standard_error;
    result["variance"] = split.variance;
    result["reference_variance"] = split.reference_variance;
    result["rel_bias2"] = split.rel_bias2;
    result["rel_variance"] = split.rel_variance;
    result["rel_reference_variance"] = split.rel_reference_variance;
  }
  return result;
}

// What a frontier runs over: a method (a hashed one per backend) after a number of frames. Configurations after
// other numbers of frames are not on one frontier: time per frame is the axis, and the image after 16 frames has had
// 16 of them.
std::string FrontierLabel(const std::string& method, const std::string& backend, std::uint32_t frames) {
  return method + (backend == "-" ? "" : "/" + backend) +
         (frames == 1 ? "" : ", " + std::to_string(frames) + " frames");
}

// Each finished configuration's place against time: whether it is on its frontier of relMSE against total time per
// frame, and the relMSE plain path tracing's frontier after as many frames reaches in the same time per frame, the
// line to beat (null when no pt configuration is that fast); and the plot of them all, OUT/pareto.png.
void MarkFrontiers(std::vector<json>& results, const std::string& scene, const fs::path& out) {
  std::vector<TimedError> points;
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (results[i].is_null()) continue;
    const json& r = results[i];
    points.push_back(
        {FrontierLabel(r["method"].get<std::string>(), r["backend"].get<std::string>(), r.value("frames", 1u)),
         r["total_s"].get<double>(), r["relmse"].get<double>()});
    at.push_back(i);
  }
  const std::vector<bool> frontier = ParetoFrontier(points);
  for (std::size_t k = 0; k < points.size(); ++k) {
    json& r = results[at[k]];
    r["frontier"] = bool(frontier[k]);
    const double pt =
        FrontierErrorAt(points, frontier, FrontierLabel("pt", "-", r.value("frames", 1u)), points[k].seconds);
    r["pt_relmse_at_equal_time"] = pt < 0.0 ? json() : json(pt);
  }
  if (!points.empty()) WritePng((out / "pareto.png").string(), RenderParetoPlot(scene, points, frontier));
}

// The second plot, OUT/bias-variance.png: relMSE's bias^2 and variance against filter width for each group of
// configurations that differ only in their filter width, when the grid sweeps two widths or more.
void PlotBiasAgainstWidth(const std::vector<json>& results, const std::string& scene, const fs::path& out) {
  std::map<std::string, WidthSeries> groups;
  std::vector<std::string> order;
  for (const json& r : results) {
    if (r.is_null() || !r["filter"].contains("filter-width")) continue;
    std::string label = r["id"].get<std::string>();
    const std::string token = "filter-width=" + r["filter"]["filter-width"].get<std::string>();
    const std::size_t at = label.find(token);
    if (at != std::string::npos) label.erase(at > 0 ? at - 1 : at, token.size() + (at > 0 ? 1 : 0));
    auto [it, inserted] = groups.try_emplace(label);
    if (inserted) order.push_back(label);
    WidthSeries& s = it->second;
    s.label = label;
    s.method = r["method"].get<std::string>();
    s.widths.push_back(std::stod(r["filter"]["filter-width"].get<std::string>()));
    s.bias2.push_back(r.value("rel_bias2", 0.0));
    s.variance.push_back(r.value("rel_variance", 0.0));
  }
  std::vector<WidthSeries> series;
  for (const std::string& label : order) {
    const WidthSeries& s = groups[label];
    if (s.widths.size() < 2) continue;
    // In increasing width: a grid may list its widths in any order.
    std::vector<std::array<double, 3>> points;
    for (std::size_t k = 0; k < s.widths.size(); ++k) points.push_back({s.widths[k], s.bias2[k], s.variance[k]});
    std::sort(points.begin(), points.end());
    WidthSeries& sorted = series.emplace_back(WidthSeries{s.label, s.method, {}, {}, {}});
    for (const auto& [width, bias2, variance] : points) {
      sorted.widths.push_back(width);
      sorted.bias2.push_back(bias2);
      sorted.variance.push_back(variance);
    }
  }
  if (!series.empty()) WritePng((out / "bias-variance.png").string(), RenderBiasVariancePlot(scene, series));
}

// The third plot, OUT/frames.png: relMSE after each frame, one line per group of configurations that differ only in
// their frames, the longest (a shorter one's frames are its first: the same traces and tables); none, and none left
// from before, without a configuration of more than one frame.
void PlotFrames(const std::vector<json>& results, const std::string& scene, const fs::path& out) {
  std::vector<FrameSeries> series;
  std::map<std::string, std::size_t> group_at;
  for (const json& r : results) {
    if (r.is_null() || !r.contains("relmse_by_frame")) continue;
    std::string label = r["id"].get<std::string>();
    const std::string token = " frames=" + std::to_string(r["frames"].get<std::uint32_t>());
    label.erase(label.find(token), token.size());
    FrameSeries s{label, r["method"].get<std::string>(), r["relmse_by_frame"].get<std::vector<double>>()};
    const auto [it, inserted] = group_at.try_emplace(label, series.size());
    if (inserted) {
      series.push_back(std::move(s));
    } else if (s.relmse.size() > series[it->second].relmse.size()) {
      series[it->second] = std::move(s);
    }
  }
  std::error_code ignored;
  fs::remove(out / "frames.png", ignored);
  if (!series.empty()) WritePng((out / "frames.png").string(), RenderFramesPlot(scene, series));
}

std::string CsvField(const json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

void WriteSummaries(const fs::path& out, const std::vector<SweepConfig>& configs, const std::vector<json>& results,
                    const std::vector<GridAxis>& axes, const std::string& scene, const std::string& reference) {
  // The trace axes the grid names, then its filter axes: a configuration's own value, or an empty field where its
  // method reads none.
  std::vector<std::string> trace_axes, filter_axes;
  for (const GridAxis& a : axes) {
    if (a.name == "max-depth" || a.name == "filtered-vertices" || a.name == "continuation-depth") {
      trace_axes.push_back(a.name);
    } else if (a.name != "spp" && a.name != "frames" && a.name != "method" && a.name != "backend") {
      filter_axes.push_back(a.name);
    }
  }
  std::ofstream csv(out / "sweep.csv");
  csv << "id,method,backend,spp,frames";
  for (const std::string& a : trace_axes) csv << "," << a;
  for (const std::string& a : filter_axes) csv << "," << a;
  const std::vector<std::string> figures = {"seeds",
                                            "trace_s",
                                            "filter_s",
                                            "total_s",
                                            "mse",
                                            "relmse",
                                            "ssim",
                                            "fireflies",
                                            "bias2",
                                            "bias2_standard_error",
                                            "mean_error",
                                            "mean_error_standard_error",
                                            "variance",
                                            "reference_variance",
                                            "rel_bias2",
                                            "rel_variance",
                                            "rel_reference_variance",
                                            "probe_failures",
                                            "aliased_slots",
                                            "rays_per_pixel",
                                            "frontier",
                                            "pt_relmse_at_equal_time"};
  for (const std::string& f : figures) csv << "," << f;
  csv << "\n";
  json all = json::array();
  for (std::size_t i = 0; i < configs.size(); ++i) {
    if (results[i].is_null()) continue;
    const json& r = results[i];
    csv << '"' << r["id"].get<std::string>() << "\"," << CsvField(r["method"]) << "," << CsvField(r["backend"]) << ","
        << CsvField(r["spp"]) << "," << CsvField(r.value("frames", json(1)));
    for (const std::string& a : trace_axes)
      csv << "," << CsvField(r.value("trace_axes", json::object()).value(a, json()));
    for (const std::string& a : filter_axes) csv << "," << CsvField(r["filter"].value(a, json()));
    for (const std::string& f : figures) csv << "," << CsvField(r.value(f, json()));
    csv << "\n";
    all.push_back(r);
  }
  std::ofstream(out / "sweep.json") << json{{"version", 1}, {"command", "sweep"}, {"configurations", all}}.dump(2)
                                    << "\n";
  WriteHtmlReport((out / "sweep.html").string(), RenderSweepHtml(scene, all, reference));
}

int Run(SweepOptions& o, bool options_only) {
  ReferenceRequest reference_request;
  ParseSize(o.size, reference_request.trace);
  reference_request.trace.seed = kReferenceSeed;
  reference_request.trace.max_depth = o.max_depth;
  reference_request.samples_per_pixel = o.reference_spp;
  reference_request.Validate();
  if (o.seeds == 0) throw ConfigError("--seeds", "must be at least 1");
  const std::vector<GridAxis> axes = ParseGrid(o.grid);
  for (const GridAxis& a : axes) {
    if (a.name == "seed") throw ConfigError("--grid", "seed is not an axis: --seeds K runs seeds 1..K");
  }
  const std::vector<SweepConfig> configs = ExpandGrid(axes);
  std::vector<FilterConfig> filter_configs;
  std::vector<TraceOptions> traces;
  for (const SweepConfig& c : configs) {
    filter_configs.push_back(FilterConfigOf(c));
    traces.push_back(TraceOf(c, reference_request.trace));
    if (c.method == "hashcache") HashCacheSettingsOf(c, filter_configs.back());
  }
  const auto [shard, shards] = ParseShard(o.shard);
  if (options_only) return kExitOk;

  const Scene scene = LoadScene(o.scene);
  const bool terminal = isatty(STDERR_FILENO) && !o.json;
  // A static scene's sequence is measured against one converged image; an animated scene's frames each against their
  // own, so it needs one per frame up to the longest sequence's last.
  std::uint32_t reference_frames = 1;
  if (!scene.animation.Static()) {
    for (const SweepConfig& c : configs) reference_frames = std::max(reference_frames, c.frames);
  }
  std::vector<Converged> converged;
  for (std::uint32_t f = 0; f < reference_frames; ++f) {
    ReferenceRequest request = reference_request;
    request.trace.frame = f;
    Converged frame;
    frame.entry = GetReferenceImage(scene, o.scene, request, o.cache.empty() ? DefaultReferenceCache() : o.cache, false,
                                    [&](std::uint32_t done, std::uint32_t total) {
                                      if (terminal) {
                                        std::fprintf(stderr, "\rsweep: the converged image of frame %u, pass %u of %u",
                                                     f, done, total);
                                      }
                                    });
    const ChannelImage channels = ReadChannelImage(frame.entry.entry.image);
    frame.image = ColourOf(channels, "");
    frame.variance = ColourOf(channels, "variance.");
    frame.channels = ColourChannels(frame.image);
    converged.push_back(std::move(frame));
  }
  const ReferenceImage& reference = converged[0].entry;
  // What a configuration is measured against: its last frame's converged image.
  const auto against = [&](const SweepConfig& c) {
    return converged[std::min<std::size_t>(c.frames - 1, converged.size() - 1)].entry.description;
  };
  const fs::path out = o.out;
  fs::create_directories(out / "configs");

  // Run in order of what is traced, so that the one-frame configurations that trace alike share their batches;
  // report in grid order.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    if (i % shards == shard - 1) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::make_tuple(configs[a].spp, configs[a].frames, TraceKey(traces[a])) <
           std::make_tuple(configs[b].spp, configs[b].frames, TraceKey(traces[b]));
  });
  std::vector<json> results(configs.size());
  Runner runner(scene);
  std::size_t done = 0, resumed = 0;
  const auto start = Clock::now();
  for (const std::size_t i : order) {
    const SweepConfig& c = configs[i];
    const std::string path = ConfigFile(out, i, c);
    const std::string description = Description(c, o, against(c));
    if (std::ifstream in(path); in) {
      json kept = json::parse(in, nullptr, false);
      if (!kept.is_discarded() && kept.value("description", "") == description) {
        results[i] = kept["result"];
        ++done;
        ++resumed;
        continue;
      }
    }
    results[i] = MeasureConfig(c, filter_configs[i], traces[i], o.seeds, converged, o.reference_spp, runner,
                               fs::path(path).replace_extension(".exr").string());
    std::ofstream(path) << json{{"description", description}, {"result", results[i]}}.dump(2) << "\n";
    ++done;
    if (terminal) {
      const double elapsed = SecondsSince(start);
      const double eta = elapsed / double(done - resumed) * double(order.size() - done);
      std::fprintf(stderr, "\rsweep: %zu of %zu configurations, %.0f s, about %.0f s to go   ", done, order.size(),
                   elapsed, eta);
    }
  }
  if (terminal) std::fprintf(stderr, "\r%78s\r", "");
  // Every configuration kept in OUT, this shard's or another's.
  for (std::size_t i = 0; i < configs.size(); ++i) {
    if (!results[i].is_null()) continue;
    if (std::ifstream in(ConfigFile(out, i, configs[i])); in) {
      const json kept = json::parse(in, nullptr, false);
      if (!kept.is_discarded() && kept.value("description", "") == Description(configs[i], o, against(configs[i]))) {
        results[i] = kept["result"];
      }
    }
  }
  MarkFrontiers(results, o.scene, out);
  PlotFrames(results, o.scene, out);
  // One seed measures the error but cannot split it into bias^2 and variance: no plot, and none left from before.
  if (o.seeds >= 2) {
    PlotBiasAgainstWidth(results, o.scene, out);
  } else {
    std::error_code ignored;
    fs::remove(out / "bias-variance.png", ignored);
  }
  WriteSummaries(
      out, configs, results, axes, o.scene,
      converged.size() > 1
          ? "each configuration's last frame's converged image of " + std::to_string(o.reference_spp) +
                " spp (frame 0's: " + reference.entry.image + ")"
          : "a converged image of " + std::to_string(o.reference_spp) + " spp (" + reference.entry.image + ")");
  std::size_t finished = 0;
  for (const json& r : results) finished += !r.is_null();
  if (o.json) {
    json all = json::array();
    for (const json& r : results) {
      if (!r.is_null()) all.push_back(r);
    }
    std::cout << json{{"version", 1},
                      {"command", "sweep"},
                      {"reference", reference.entry.image},
                      {"configurations", all},
                      {"run", done - resumed},
                      {"resumed", resumed},
                      {"seconds", SecondsSince(start)}}
                     .dump(2)
              << "\n";
  } else {
    std::printf("%-58s %8s %8s %9s %9s %9s %9s %7s\n", "configuration", "trace s", "filter s", "relMSE", "MSE",
                "bias^2", "variance", "SSIM");
    for (const json& r : results) {
      if (r.is_null()) continue;
      std::printf("%-58s %8.4f %8.4f %9.4g %9.4g %9.3g %9.4g %7.4f\n", r["id"].get<std::string>().c_str(),
                  r["trace_s"].get<double>(), r["filter_s"].get<double>(), r["relmse"].get<double>(),
                  r["mse"].get<double>(), r.value("bias2", 0.0), r.value("variance", 0.0), r["ssim"].get<double>());
    }
    std::printf("sweep: %zu configurations run, %zu kept from before, %zu of %zu in %s (%.1f s)\n", done - resumed,
                resumed, finished, configs.size(), (out / "sweep.csv").c_str(), SecondsSince(start));
  }
  return kExitOk;
}

}  // namespace

void AddSweepCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* c = app.add_subcommand(
      "sweep",
      "What accuracy costs in time: every configuration of a grid, traced and filtered with K seeds, timed "
      "and measured against the scene's converged image (relMSE, SSIM, bias^2 and variance)");
  c->add_option("scene", o->scene, "A built-in scene or a scene file")->required();
  c->add_option("--grid", o->grid,
                "Axes and values, e.g. \"spp=1,4; frames=1,16; filter-width=2,4; method=pt,hpsf,nhpsf,anhpsf,radius,"
                "screen,hashcache; backend=reference,emulated\" (trace axes: max-depth, filtered-vertices, "
                "continuation-depth, survival, path-graph, cache-resolution, cache-store, cache-length, cache-update; "
                "other axes: any filter option without its dashes)")
      ->required()
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);  // a later --grid replaces an earlier one
  c->add_option("--seeds", o->seeds, "Independent seeds per configuration (1..K); 2 or more split the error")
      ->capture_default_str();
  c->add_option("--size", o->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  c->add_option("--reference-spp", o->reference_spp, "Samples per pixel of the converged image (multiple of 16)")
      ->capture_default_str();
  c->add_option("--max-depth", o->max_depth, "Surface vertices per path; -1: unbounded")->capture_default_str();
  c->add_option("--cache", o->cache, "The converged images' cache (see hpsf reference)");
  c->add_option("--shard", o->shard, "Run configurations I, I + N, ... of the grid")->capture_default_str();
  c->add_option("--out", o->out,
                "Where each configuration's result and its first seed's image (configs/), sweep.csv and sweep.json go")
      ->capture_default_str();
  c->add_flag("--json", o->json, "Print the versioned report as JSON");
  c->callback([o, &context] { context.exit_code = Run(*o, context.options_only); });
}

}  // namespace hpsf
