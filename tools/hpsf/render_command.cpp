#include "tools/hpsf/render_command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/backend_registry.h"
#include "core/error.h"
#include "core/record_file.h"
#include "tools/hpsf/batch_input.h"
#include "tools/hpsf/bounce_options.h"
#include "tools/hpsf/effect_report.h"
#include "tools/hpsf/filter_output.h"
#include "tools/hpsf/frame_soundness.h"
#include "tools/hpsf/image_file.h"
#include "tools/hpsf/image_size.h"
#include "tools/hpsf/previous_table_decision.h"
#include "tools/hpsf/seconds_since.h"
#include "tools/hpsf/series_convergence.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

struct RenderOptions {
  std::string scene;
  std::string output;
  std::string backend = "reference";
  std::string size = "256x256";
  std::string dump_records;
  std::uint32_t frames = 1;
  std::string frame_out;
  TraceOptions trace;
  FilterOptions filter;
  EmulatorFlags emulator;
  bool json = false;
};

// Progress on a terminal only, so logs and pipes stay clean.
std::function<void(std::uint32_t, std::uint32_t)> TerminalProgress() {
  if (!isatty(STDERR_FILENO)) return {};
  return [](std::uint32_t done, std::uint32_t total) { std::fprintf(stderr, "\rtracing %3u%%", 100 * done / total); };
}

// --frame-out's pattern: one "{frame}", replaced by the frame number padded to four digits; an .exr name.
constexpr const char* kFramePlaceholder = "{frame}";

void CheckFramePattern(const std::string& pattern) {
  const std::size_t at = pattern.find(kFramePlaceholder);
  if (at == std::string::npos || pattern.find(kFramePlaceholder, at + 1) != std::string::npos) {
    throw ConfigError("--frame-out", "needs exactly one {frame} in '" + pattern + "', e.g. out/frame-{frame}.exr");
  }
  if (pattern.size() < 4 || pattern.compare(pattern.size() - 4, 4, ".exr") != 0) {
    throw ConfigError("--frame-out", "must name .exr files; got '" + pattern + "'");
  }
}

std::string FramePath(const std::string& pattern, std::uint32_t frame) {
  char number[16];
  std::snprintf(number, sizeof number, "%04u", frame);
  std::string path = pattern;
  return path.replace(path.find(kFramePlaceholder), std::string(kFramePlaceholder).size(), number);
}

// One frame of a sequence through the backend's table (core/backend.h). The last frame goes to `request.output`
// (-o) and, given a --frame-out pattern, to its frame's file too (copied, not filtered twice); an earlier frame
// goes to its frame's file, or only into the table. `frame` (its JSON entry) gains the output, the filter time and
// the eviction and temporal figures; the last frame's FilterAndWrite report is returned, an empty one otherwise.
nlohmann::json FilterSequenceFrame(BackendInstance& backend, const RecordBatch& batch, const FilterConfig& config,
                                   const FilterOptions& filter, const OutputRequest& request,
                                   const std::string& frame_out, bool last, nlohmann::json& frame) {
  const std::string frame_path = frame_out.empty() ? "" : FramePath(frame_out, config.frame);
  nlohmann::json report;
  if (last) {
    report = FilterAndWrite(backend, batch, config, filter, request);
    if (!frame_path.empty()) frame["output"] = CopyImageFiles(request.output, frame_path);
    frame["filter_s"] = report["timings"]["filter_s"];
  } else if (!frame_path.empty()) {
    const nlohmann::json written =
        FilterAndWrite(backend, batch, config, filter, {request.scene, request.backend, frame_path});
    frame["output"] = written["output"];
    frame["filter_s"] = written["timings"]["filter_s"];
  } else {
    const auto filter_start = std::chrono::steady_clock::now();
    const Image& image = backend.backend->FilterFrame(batch, config);
    frame["filter_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - filter_start).count();
    RequireSoundFrame(*backend.backend, image, config);
  }
  if (config.eviction.enabled()) frame["eviction"] = LastFrameEviction(*backend.backend);
  if (config.temporal.blends()) frame["temporal"] = LastFrameTemporal(*backend.backend);
  if (config.level_seed.enabled) frame["level_seed"] = LastFrameLevelSeed(*backend.backend);
  if (config.compaction != Compaction::kNone) frame["compaction"] = LastFrameCompaction(*backend.backend);
  if (config.accumulation == Accumulation::kPackedDecimal) frame["settle"] = LastFrameSettle(*backend.backend);
  return report;
}

void RunRender(RenderOptions& o, bool options_only) {
  FindBackend(o.backend, "--backend");
  const EmulatorOptions emulator = ResolveEmulatorOptions(o.emulator);
  ParseSize(o.size, o.trace);
  o.trace.seed = o.filter.config.seed;
  o.filter.config.frames = o.frames;
  FilterConfig config = ResolveFilterConfig(o.filter);  // reject bad filter options before spending time tracing
  TraceScatteredVertices(config, o.trace);
  CheckAdaptiveTrace(config, o.trace);
  o.trace.Validate();
  CheckVarianceSamples(o.filter, o.trace.samples_per_pixel, "--spp");
  if (std::uint64_t(o.trace.frame) + o.frames - 1 > 0xFFFFFFFFu) {
    throw ConfigError("--frames", "frames " + std::to_string(o.trace.frame) + " + " + std::to_string(o.frames) +
                                      " run past the last frame number, 2^32 - 1");
  }
  if (!o.frame_out.empty()) CheckFramePattern(o.frame_out);
  const Defect defect = ParseDefect(o.emulator.defect);
  if (options_only) return;
  const Scene scene = LoadScene(o.scene);

  // Frame after frame through one backend, whose table carries over (core/backend.h); the last frame goes to -o,
  // each one to --frame-out's file when given.
  BackendInstance backend = MakeBackend(o.backend, emulator, defect, o.emulator.vulkan);
  const std::uint32_t first = o.trace.frame;
  nlohmann::json report, per_frame = nlohmann::json::array();
  std::optional<RecordFileWriter> dump;
  if (!o.dump_records.empty()) dump.emplace(o.dump_records, o.frames);
  TraceResult traced;
  double trace_seconds = 0.0;
  // A static scene is built for tracing once for the whole sequence, an animated one for each frame (the effect
  // "animation", core/effect_plan.h); scene_s is the build's time, zero where it was skipped.
  const SceneFacts facts = FactsOf(scene);
  const std::vector<EffectDecision> plan = PlanSequenceEffects(config, facts, o.frames);
  std::optional<PreparedScene> prepared;
  PathContinuation continuation;  // A-nHPSF's kept paths, from frame to frame
  std::uint64_t continued = 0, culled = 0, cut = 0;
  double graph_variance_max = 0.0;
  SeriesConvergence series;  // with the transport: whether the fed-back light settled
  for (std::uint32_t k = 0; k < o.frames; ++k) {
    o.trace.frame = first + k;
    config.frame = o.trace.frame;  // the jitter's random numbers follow the frame too
    const auto build_start = std::chrono::steady_clock::now();
    double scene_seconds = 0.0;
    if (!prepared || RebuildsScenePerFrame(config, facts)) {
      prepared.reset();
      prepared.emplace(scene, o.trace.frame);
      scene_seconds = SecondsSince(build_start);
    }
    // Survival and path graphs read the table the frame before left in the rendering backend
    // (core/previous_table_view.h).
    const HashedRun* hashed = backend.backend->LastHashedRun();
    const std::optional<PreviousTableView> table_before =
        config.TracerReadsTable() ? FramePreviousTableView(config, o.trace, *prepared, k,
                                                           k > 0 ? backend.backend->LastExactResult() : nullptr,
                                                           k > 0 && hashed ? &hashed->table : nullptr)
                                  : std::nullopt;
    const auto start = std::chrono::steady_clock::now();
    const auto progress = TerminalProgress();
    traced = TraceRecords(*prepared, o.trace, progress, &continuation, table_before ? &*table_before : nullptr);
    continued += traced.stats.continued;
    culled += traced.stats.culled;
    cut += traced.stats.cut;
    graph_variance_max = std::max(graph_variance_max, traced.stats.graph_variance_max);
    if (progress) std::fprintf(stderr, "\r              \r");
    trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const bool last = k + 1 == o.frames;
    if (dump) dump->Append(traced.batch);
    nlohmann::json frame = {{"frame", o.trace.frame}, {"scene_s", scene_seconds}, {"trace_s", trace_seconds}};
    nlohmann::json written = FilterSequenceFrame(backend, traced.batch, config, o.filter,
                                                 {scene.name, o.backend, o.output}, o.frame_out, last, frame);
    if (last) report = std::move(written);
    const FilterResult* exact = backend.backend->LastExactResult();
    series.means.push_back(ImageMean(exact ? exact->image : backend.backend->LastHashedRun()->image));
    per_frame.push_back(frame);
  }
  if (dump) dump->Finish();
  report["version"] = 1;
  report["command"] = "render";
  report["scene"] = scene.name;
  report["trace"] = {{"width", o.trace.width},
                     {"height", o.trace.height},
                     {"spp", o.trace.samples_per_pixel},
                     {"max_depth", o.trace.max_depth},
                     {"filter_bounce", o.trace.filter_bounce},
                     {"filtered_vertices", o.trace.filtered_vertices},
                     {"continuation_depth", o.trace.continuation_depth},
                     {"continued", continued},
                     {"culled", culled},
                     {"cut", cut},
                     {"graph_variance_max", graph_variance_max},
                     {"threads", o.trace.threads},
                     {"frame", o.trace.frame},
                     {"first_frame", first},
                     {"frames", o.frames}};
  if (o.frames > 1) report["frames"] = per_frame;
  if (config.transport && o.frames > 1) report["series"] = series.ToJson();
  report["effects"] = EffectsJson(plan);
  report["timings"]["scene_s"] = per_frame.back()["scene_s"];
  report["rays"] = traced.stats.Rays();
  report["timings"]["trace_s"] = trace_seconds;
  report["rays_per_s"] = trace_seconds > 0.0 ? double(traced.stats.Rays()) / trace_seconds : 0.0;
  if (!o.dump_records.empty()) report["records_file"] = o.dump_records;
  PrintReport(report, o.json);
  if (!o.json && !EffectsLine(plan, o.frames).empty()) std::cout << EffectsLine(plan, o.frames) << "\n";
}

struct ReplayOptions {
  std::string records;
  std::string output;
  std::string backend = "reference";
  std::string frame_out;
  FilterOptions filter;
  EmulatorFlags emulator;
  bool json = false;
};

// Every frame of the file through one table, each as its own frame number; the last goes to -o, each one to
// --frame-out's file when given.
void RunReplay(ReplayOptions& o, bool options_only) {
  FindBackend(o.backend, "--backend");
  const EmulatorOptions emulator = ResolveEmulatorOptions(o.emulator);
  ResolveFilterConfig(o.filter);
  if (!o.frame_out.empty()) CheckFramePattern(o.frame_out);
  const Defect defect = ParseDefect(o.emulator.defect);
  if (options_only) return;
  const std::vector<RecordBatch> frames = ReadRecordFrames(o.records);
  o.filter.config.frames = std::uint32_t(frames.size());  // fixed64's F leaves room for all of them
  FilterConfig config = ResolveFilterConfig(o.filter);
  CheckTransportInput(o.records, frames, config);
  BackendInstance backend = MakeBackend(o.backend, emulator, defect, o.emulator.vulkan);
  // Records bring no scene: nothing is traced, and whether it moved is not known.
  const std::vector<EffectDecision> plan = PlanSequenceEffects(config, SceneFacts{false, false}, config.frames);
  nlohmann::json report, per_frame = nlohmann::json::array();
  SeriesConvergence series;  // with the transport: whether the fed-back light settled
  for (std::size_t k = 0; k < frames.size(); ++k) {
    config.frame = frames[k].frame;
    nlohmann::json frame = {{"frame", config.frame}};
    const bool last = k + 1 == frames.size();
    nlohmann::json written = FilterSequenceFrame(backend, frames[k], config, o.filter, {o.records, o.backend, o.output},
                                                 o.frame_out, last, frame);
    if (last) report = std::move(written);
    const FilterResult* exact = backend.backend->LastExactResult();
    series.means.push_back(ImageMean(exact ? exact->image : backend.backend->LastHashedRun()->image));
    per_frame.push_back(frame);
  }
  report["version"] = 1;
  report["command"] = "replay";
  report["records_file"] = o.records;
  if (frames.size() > 1) report["frames"] = per_frame;
  if (config.transport && frames.size() > 1) report["series"] = series.ToJson();
  report["effects"] = EffectsJson(plan);
  PrintReport(report, o.json);
  if (!o.json && !EffectsLine(plan, config.frames).empty()) std::cout << EffectsLine(plan, config.frames) << "\n";
}

}  // namespace

void AddRenderCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* c =
      app.add_subcommand("render", "Trace a scene into sample records, filter them, write OUT.exr and OUT.png");
  c->add_option("scene", o->scene,
                "A built-in scene (cornell, furnace, cornell-far-1e5, cornell-far-1e7, cornell-tiny, "
                "cornell-zero-red) or a scene file")
      ->required();
  c->add_option("-o,--output", o->output, "The EXR to write; the PNG preview goes beside it")->required();
  c->add_option("--backend", o->backend, "Filter backend: " + BackendNames())->capture_default_str();
  c->add_option("--spp", o->trace.samples_per_pixel, "Samples per pixel")->capture_default_str();
  c->add_option("--size", o->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  c->add_option("--max-depth", o->trace.max_depth,
                "Surface vertices per path, the series truncated after the last one's emission; -1: unbounded")
      ->capture_default_str();
  c->add_option("--filter-bounce", o->trace.filter_bounce, "Which diffuse vertex is filtered; 0: the primary hit")
      ->capture_default_str();
  AddBounceOptions(*c, o->trace);
  AddAdaptiveTraceOptions(*c, o->filter.config);
  c->add_option("--threads", o->trace.threads, "Tracing threads; 0: all cores (output bits do not depend on it)")
      ->capture_default_str();
  c->add_option("--frame", o->trace.frame,
                "Trace an animated scene at this frame (its keyframes, and the frame in every random number); "
                "the first of --frames")
      ->capture_default_str();
  c->add_option("--frames", o->frames,
                "Trace and filter this many frames, from --frame on, through one table kept from frame to frame "
                "(temporal integration); -o gets the last")
      ->capture_default_str();
  c->add_option("--frame-out", o->frame_out,
                "Also write every frame, to PATTERN with {frame} for its number: out/f-{frame}.exr");
  c->add_option("--dump-records", o->dump_records, "Also write the traced frames to FILE.hpsfv");
  c->add_flag("--json", o->json, "Print the report as JSON");
  AddFilterOptions(*c, o->filter);
  AddEmulatorOptions(*c, o->emulator);
  c->callback([o, &context] { RunRender(*o, context.options_only); });
}

void AddReplayCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<ReplayOptions>();
  CLI::App* c =
      app.add_subcommand("replay", "Filter recorded frames (.hpsfv) and write the last to OUT.exr and OUT.png");
  c->add_option("records", o->records, "The .hpsfv file; its frames go through one table, each as its number")
      ->required();
  c->add_option("-o,--output", o->output, "The EXR to write; the PNG preview goes beside it")->required();
  c->add_option("--backend", o->backend, "Filter backend: " + BackendNames())->capture_default_str();
  c->add_option("--frame-out", o->frame_out,
                "Also write every frame, to PATTERN with {frame} for its number: out/f-{frame}.exr");
  c->add_flag("--json", o->json, "Print the report as JSON");
  AddFilterOptions(*c, o->filter);
  AddEmulatorOptions(*c, o->emulator);
  c->callback([o, &context] { RunReplay(*o, context.options_only); });
}

}  // namespace hpsf
