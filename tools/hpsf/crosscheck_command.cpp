#include "tools/hpsf/crosscheck_command.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <span>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "tools/hpsf/backend_options.h"
#include "tools/hpsf/batch_input.h"
#include "tools/hpsf/bounce_options.h"
#include "tools/hpsf/filter_options.h"
#include "tools/hpsf/hashcache_crosscheck.h"
#include "tools/hpsf/hashcache_options.h"
#include "tools/hpsf/repro_bundle.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"
#include "verifier/contract/crosscheck.h"
#include "verifier/contract/run_capture.h"
#include "verifier/gate/table_declaration.h"

namespace hpsf {
namespace {

struct CrosscheckOptions {
  std::string input;
  std::string backends = "reference,emulated,vulkan";
  std::string repro_dir = "hpsf-repro";
  std::string report_file;
  std::string capture_dir;
  std::string size = "128x128";
  std::uint32_t frames = 1;  // a scene's; a record file's are all it holds
  bool frames_given = false, frame_given = false;
  TraceOptions trace;
  FilterOptions filter;
  EmulatorFlags emulator;
  HashCacheFlags hashcache;
  bool json = false;
  std::vector<std::string> arguments;  // as given, for the bundle's command line
};

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) items.push_back(item);
  return items;
}

// The same check on the same records: every option that decides the outcome, the input replaced by the recorded
// frames (which carry their numbers, so --frame goes; and the tracer's decisions, survival's culls and path graphs'
// own lights, so --survival and --path-graph go), and a bundle of its own so the original is kept for comparison.
// Survival also chose F and G with room for its weights: the bundle gives the run's own.
void WriteBundle(const CrosscheckOptions& o, std::span<const RecordBatch> frames, const CrosscheckReport& report) {
  const bool survival = std::find(o.arguments.begin(), o.arguments.end(), "--survival") != o.arguments.end();
  std::vector<std::string> arguments;
  for (std::size_t i = 0; i < o.arguments.size(); ++i) {
    const std::string& a = o.arguments[i];
    if (a == "--repro-dir" || a == "--frame" || a == "--report" || a == "--capture" || a == "--survival" ||
        a == "--path-graph" || (survival && (a == "--fixed-point-bits" || a == "--square-bits"))) {
      ++i;
      continue;
    }
    if (a != "--json") arguments.push_back(a);
  }
  if (survival) {
    arguments.insert(arguments.end(), {"--fixed-point-bits", std::to_string(report.fixed_point_bits)});
    if (report.square_bits) arguments.insert(arguments.end(), {"--square-bits", std::to_string(*report.square_bits)});
  }
  WriteReproBundle(o.repro_dir, frames, report, arguments);
  std::cerr << "hpsf: the contract does not hold; repro bundle in " << o.repro_dir
            << " (records.hpsfv, report.json; reproduce.sh reruns the check and writes reproduced.json)\n";
}

// A record file brings its own frames and their numbers; a scene is traced for --frames from --frame on.
void CheckFrameOptions(const CrosscheckOptions& o) {
  if (IsRecordFile(o.input)) {
    if (o.frame_given) throw ConfigError("--frame", o.input + " carries its frames' numbers; --frame is for a scene");
    return;
  }
  if (std::uint64_t(o.trace.frame) + o.frames - 1 > 0xFFFFFFFFu) {
    throw ConfigError("--frames", "frames " + std::to_string(o.trace.frame) + " + " + std::to_string(o.frames) +
                                      " run past the last frame number, 2^32 - 1");
  }
}

// Every hashed backend's frames as captures, DIR/BACKEND-frame-N.hpsfc, through the writer a team's engine calls.
void ObserveIntoCaptures(Crosschecker& checker, const std::string& dir, const FilterConfig& config) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw ConfigError("--capture", dir + ": " + error.message());
  checker.ObserveFrames([dir, declaration = TableDeclarationText(config)](
                            const std::string& backend, const RecordBatch& batch, std::uint32_t frame,
                            const HashedRun& run, const HashTableDump* before) {
    const std::string path = dir + "/" + backend + "-frame-" + std::to_string(frame) + ".hpsfc";
    WriteRunCapture(path, declaration, batch, frame, run, before);
  });
}

// --method hashcache: the HashCache on each backend over the scene's frames (tools/hpsf/hashcache_crosscheck.h).
int RunHashCache(CrosscheckOptions& o, const FilterConfig& config, const EmulatorOptions& emulator, bool options_only) {
  if (IsRecordFile(o.input)) {
    throw ConfigError("--method", o.input + " holds records; the HashCache caches samples it traces from a scene");
  }
  if (ParseDefect(o.emulator.defect) != Defect::kNone) {
    throw ConfigError("--inject-defect", "breaks hpsf's own table's passes, not the HashCache's");
  }
  const HashCacheSettings settings = ResolveHashCacheSettings(o.hashcache, config.accumulation, o.frames, config.seed);
  const CacheSampling sampling = ResolveCacheSampling(o.hashcache);
  const HashCacheUpdateDefect defect = ResolveCacheDefect(o.hashcache);
  ResolveTraceOptions(o.input, o.size, o.trace, config.seed);
  CheckFrameOptions(o);
  if (options_only) return kExitOk;
  const HashCacheCrosscheck result = CrosscheckHashCache(LoadScene(o.input), o.trace, o.frames, SplitList(o.backends),
                                                         settings, sampling, emulator, o.emulator.vulkan, defect);
  if (!o.report_file.empty()) std::ofstream(o.report_file) << result.report.dump(2) << "\n";
  if (o.json) {
    std::cout << result.report.dump(2) << "\n";
  } else {
    std::cout << result.text;
  }
  if (result.passed) return kExitOk;
  std::vector<std::string> arguments;
  for (std::size_t i = 0; i < o.arguments.size(); ++i) {
    const std::string& a = o.arguments[i];
    if (a == "--repro-dir" || a == "--report") {
      ++i;
      continue;
    }
    if (a != "--json") arguments.push_back(a);
  }
  WriteHashCacheBundle(o.repro_dir, o.input, arguments, result.report);
  std::cerr << "hpsf: the HashCache's checker found problems (seed " << config.seed << "); repro bundle in "
            << o.repro_dir << " (report.json; reproduce.sh reruns the check and writes reproduced.json)\n";
  return kExitCheckFailed;
}

int Run(CrosscheckOptions& o, bool options_only) {
  o.filter.config.frames = o.frames;
  FilterConfig config = ResolveFilterConfig(o.filter);
  const EmulatorOptions emulator = ResolveEmulatorOptions(o.emulator);
  // Bad names are bad input before any tracing; the Vulkan device opens at the first check.
  Crosschecker checker(SplitList(o.backends), ParseDefect(o.emulator.defect), o.emulator.vulkan);
  if (HashCacheMethod(o.hashcache)) return RunHashCache(o, config, emulator, options_only);
  TraceScatteredVertices(config, o.trace);
  CheckAdaptiveTrace(config, o.trace);
  if (config.survival.enabled() && IsRecordFile(o.input)) {
    throw ConfigError("--survival", o.input +
                                        ": survival decides while a scene is traced; a record file's paths were "
                                        "decided when it was recorded");
  }
  ResolveTraceOptions(o.input, o.size, o.trace, config.seed);
  CheckFrameOptions(o);
  if (options_only) return kExitOk;
  const std::vector<RecordBatch> frames = LoadOrTraceFrames(o.input, o.trace, o.frames, config);
  CheckTransportInput(o.input, frames, config);
  if (o.frames_given && frames.size() != o.frames) {
    throw ConfigError("--frames",
                      o.input + " holds " + std::to_string(frames.size()) + " frames, not " + std::to_string(o.frames));
  }
  config.frames = std::uint32_t(frames.size());  // fixed64's F leaves room for all of them
  if (!o.capture_dir.empty()) ObserveIntoCaptures(checker, o.capture_dir, config);
  const CrosscheckReport report = checker.CheckFrames(frames, config, emulator);
  if (!o.report_file.empty()) std::ofstream(o.report_file) << report.ToJson().dump(2) << "\n";
  if (o.json) {
    std::cout << report.ToJson().dump(2) << "\n";
  } else {
    std::cout << report.ToText();
  }
  if (report.Passed()) return kExitOk;
  WriteBundle(o, frames, report);
  return kExitCheckFailed;
}

}  // namespace

void AddCrosscheckCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<CrosscheckOptions>();
  CLI::App* c =
      app.add_subcommand("crosscheck", "Run the backends on one batch and judge them by the cross-check contract");
  c->add_option("input", o->input, "A scene (built-in name or file) to trace, or a recorded batch FILE.hpsfv")
      ->required();
  c->add_option("--backends", o->backends, "Comma-separated: reference, emulated, vulkan")->capture_default_str();
  c->add_option("--size", o->size, "Traced image size WIDTHxHEIGHT")->capture_default_str();
  c->add_option("--spp", o->trace.samples_per_pixel, "Samples per pixel")->capture_default_str();
  c->add_option("--max-depth", o->trace.max_depth,
                "Surface vertices per path, the series truncated after the last one's emission; -1: unbounded")
      ->capture_default_str();
  c->add_option("--filter-bounce", o->trace.filter_bounce, "Which diffuse vertex is filtered")->capture_default_str();
  AddBounceOptions(*c, o->trace);
  AddAdaptiveTraceOptions(*c, o->filter.config);
  c->add_option("--frames", o->frames,
                "Check a sequence of this many frames through one table per backend (a scene: traced from --frame "
                "on; a record file: must equal its frames; default every frame of a file, one of a scene)");
  c->add_option("--frame", o->trace.frame,
                "A scene's first frame (its keyframes, and the frame in every random number)")
      ->capture_default_str();
  c->add_option("--repro-dir", o->repro_dir, "Where a failing check writes its repro bundle")->capture_default_str();
  c->add_flag("--json", o->json, "Print the versioned report as JSON");
  c->add_option("--report", o->report_file, "Also write the versioned JSON report to FILE (hpsf check reads it)");
  c->add_option("--capture", o->capture_dir,
                "Write each hashed backend's frames as captures to DIR (BACKEND-frame-N.hpsfc), for hpsf judge");
  AddFilterOptions(*c, o->filter);
  AddEmulatorOptions(*c, o->emulator);
  AddHashCacheOptions(c, o->hashcache);
  c->callback([o, c, &context] {
    o->frames_given = c->get_option("--frames")->count() > 0;
    o->frame_given = c->get_option("--frame")->count() > 0;
    context.exit_code = Run(*o, context.options_only);
  });
  c->parse_complete_callback([o, c] {
    // Keep the given options for the bundle's command line.
    o->arguments.clear();
    for (const CLI::Option* option : c->get_options()) {
      if (option->count() == 0 || option->get_name().empty() || option->get_name() == "--help") continue;
      if (option->get_positional()) continue;
      if (option->get_type_size() == 0) {
        o->arguments.push_back(option->get_name());
        continue;
      }
      for (const std::string& value : option->results()) {
        o->arguments.push_back(option->get_name());
        o->arguments.push_back(value);
      }
    }
  });
}

}  // namespace hpsf
