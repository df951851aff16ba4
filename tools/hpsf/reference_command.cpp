#include "tools/hpsf/reference_command.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "tools/hpsf/image_file.h"
#include "tools/hpsf/image_size.h"
#include "tools/hpsf/reference_cache.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

struct ReferenceOptions {
  std::string scene;
  std::string size = "256x256";
  ReferenceRequest request;
  std::string cache;
  std::string output;
  bool refresh = false;
  bool json = false;
};

int Run(ReferenceOptions& o, bool options_only) {
  ParseSize(o.size, o.request.trace);
  o.request.Validate();
  if (options_only) return kExitOk;
  const Scene scene = LoadScene(o.scene);
  const std::string folder = o.cache.empty() ? DefaultReferenceCache() : o.cache;
  const bool terminal = isatty(STDERR_FILENO) && !o.json;
  const ReferenceImage reference =
      GetReferenceImage(scene, o.scene, o.request, folder, o.refresh, [&](std::uint32_t done, std::uint32_t total) {
        if (terminal) std::fprintf(stderr, "\rreference: pass %u of %u", done, total);
      });
  if (terminal && !reference.cached) std::fprintf(stderr, "\r%40s\r", "");
  const CachedReference& entry = reference.entry;
  const std::string& description = reference.description;
  const bool cached = reference.cached;
  const double seconds = reference.seconds;
  if (!o.output.empty()) CopyImageFiles(entry.image, o.output);
  if (o.json) {
    nlohmann::json report = {
        {"version", 1},     {"command", "reference"}, {"key", entry.key},          {"image", entry.image},
        {"cached", cached}, {"seconds", seconds},     {"description", description}};
    if (!o.output.empty()) report["output"] = o.output;
    std::cout << report.dump(2) << "\n";
  } else {
    std::printf("reference: %s, %s (%s in %.2f s): %s\n", o.scene.c_str(), description.c_str(),
                cached ? "cached" : "rendered", seconds, entry.image.c_str());
    if (!o.output.empty()) std::printf("wrote %s\n", o.output.c_str());
  }
  return kExitOk;
}

}  // namespace

void AddReferenceCommand(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<ReferenceOptions>();
  CLI::App* c = app.add_subcommand(
      "reference",
      "A scene's converged image (path tracing at many samples, with each pixel's variance), rendered "
      "once and cached by the scene's content and the tracer version, to measure error against");
  c->add_option("scene", o->scene, "A built-in scene or a scene file")->required();
  c->add_option("--size", o->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  c->add_option("--spp", o->request.samples_per_pixel, "Samples per pixel, a multiple of --pass-spp")
      ->capture_default_str();
  c->add_option("--pass-spp", o->request.pass_samples,
                "Samples per pixel traced at once; the variance comes from the spread of the passes")
      ->capture_default_str();
  c->add_option("--seed", o->request.trace.seed, "Seed of every random number")->capture_default_str();
  c->add_option("--frame", o->request.trace.frame, "The frame of an animated scene")->capture_default_str();
  c->add_option("--max-depth", o->request.trace.max_depth,
                "Surface vertices per path, the series truncated after the last one's emission; -1: unbounded")
      ->capture_default_str();
  c->add_option("--cache", o->cache,
                "The cache folder (default $HPSF_CACHE, $XDG_CACHE_HOME/hpsf/references or ~/.cache/hpsf/references)");
  c->add_option("-o,--output", o->output, "Also copy the image (EXR with variance channels, and its PNG) here");
  c->add_flag("--refresh", o->refresh, "Render again even when the cache holds the image");
  c->add_flag("--json", o->json, "Print the versioned report as JSON");
  c->callback([o, &context] { context.exit_code = Run(*o, context.options_only); });
}

}  // namespace hpsf
