#include "tools/hpsf/hashcache_crosscheck.h"

#include <filesystem>
#include <fstream>
#include <memory>

#include "core/backend_registry.h"
#include "tools/hpsf/version.h"
#include "tracer/path_tracer.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

using nlohmann::json;

constexpr std::size_t kFailuresShown = 20;  // per level; the rest are counted

std::string Quoted(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

HashCacheCrosscheck CrosscheckHashCache(const Scene& scene, TraceOptions trace, std::uint32_t frames,
                                        const std::vector<std::string>& backends, const HashCacheSettings& settings,
                                        const CacheSampling& sampling, const EmulatorOptions& emulator,
                                        const VulkanBackendOptions& vulkan, HashCacheUpdateDefect defect) {
  std::unique_ptr<VulkanDevice> device;
  std::vector<std::string> names;
  std::vector<std::unique_ptr<HashCacheRun>> runs;
  for (const std::string& name : backends) {
    const BackendInfo& info = FindBackend(name, "--backends");
    if (info.kind == BackendKind::kVulkan && !device) {
      device = std::make_unique<VulkanDevice>(vulkan.device_filter, vulkan.staging);
    }
    names.push_back(info.name);
    runs.push_back(std::make_unique<HashCacheRun>(info, settings, emulator, device.get(), defect));
  }
  const std::uint32_t first = trace.frame;
  for (std::uint32_t f = 0; f < frames; ++f) {
    trace.frame = first + f;
    const PreparedScene prepared(scene, trace.frame);
    std::vector<OccupancyTriangle> triangles;
    for (const Triangle& t : prepared.scene().triangles) triangles.push_back({t.p0, t.p1, t.p2});
    const CacheTraceResult samples = TraceCacheSamples(prepared, trace, sampling);
    for (std::unique_ptr<HashCacheRun>& run : runs) {
      run->Prepare(triangles, scene.name);
      run->Update(samples.samples);
    }
  }
  HashCacheCrosscheck result;
  json construction = json::array(), updates = json::array(), per_backend = json::array();
  std::size_t construction_problems = 0, update_problems = 0;
  for (std::size_t b = 0; b < runs.size(); ++b) {
    const HashCacheRun& run = *runs[b];
    for (const std::string& problem : run.problems()) {
      const bool built = problem.rfind("construction", 0) == 0;
      std::size_t& count = built ? construction_problems : update_problems;
      if (count++ < kFailuresShown) (built ? construction : updates).push_back(names[b] + ": " + problem);
    }
    per_backend.push_back({{"backend", names[b]},
                           {"builds", run.timings().builds},
                           {"map_attempts", run.timings().attempts},
                           {"levels", run.cache().levels.size()},
                           {"missed_samples", run.missed()},
                           {"problems", run.problems().size()}});
    result.text += "hashcache on " + names[b] + ": " + std::to_string(frames) + " frames, " +
                   std::to_string(run.timings().builds) + " constructions: " +
                   (run.problems().empty()
                        ? "passed\n"
                        : std::to_string(run.problems().size()) + " problems, the first: " + run.problems()[0] + "\n");
  }
  if (construction_problems > kFailuresShown) {
    construction.push_back("... and " + std::to_string(construction_problems - kFailuresShown) + " more");
  }
  if (update_problems > kFailuresShown) {
    updates.push_back("... and " + std::to_string(update_problems - kFailuresShown) + " more");
  }
  result.passed = construction_problems == 0 && update_problems == 0;
  const HashCache& cache = runs.front()->cache();
  result.report = {{"version", 2},
                   {"method", "hashcache"},
                   {"accumulation", ToString(settings.accumulation)},
                   {"fixed_point_bits", cache.fixed_point_bits},
                   {"frames", frames},
                   {"passed", result.passed},
                   {"quality", json::array()},
                   {"levels",
                    {{{"level", 1},
                      {"name", "hashcache construction"},
                      {"applicable", true},
                      {"passed", construction_problems == 0},
                      {"failures", construction}},
                     {{"level", 2},
                      {"name", "hashcache updates"},
                      {"applicable", true},
                      {"passed", update_problems == 0},
                      {"failures", updates}}}},
                   {"hashcache",
                    {{"resolution_log2", settings.resolution_log2},
                     {"update", settings.update == HashCacheUpdateRule::kAtomics ? "atomics" : "sort-reduce"},
                     {"cache_store", sampling.store},
                     {"cache_length", sampling.length},
                     {"seed", settings.seed},
                     {"backends", per_backend}}}};
  if (device) result.report["vulkan_device"] = device->info().name;
  return result;
}

void WriteHashCacheBundle(const std::string& dir, const std::string& input, const std::vector<std::string>& arguments,
                          const json& report) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  std::ofstream(fs::path(dir) / "report.json") << report.dump(2) << "\n";
  std::string scene = input;
  if (fs::is_regular_file(input)) {
    fs::copy_file(input, fs::path(dir) / "scene.json", fs::copy_options::overwrite_existing);
    scene = "scene.json";
  }
  std::string options;
  for (const std::string& a : arguments) options.append(" ").append(Quoted(a));
  std::ofstream(fs::path(dir) / "reproduce.sh")
      << "#!/bin/sh\n"
      << "# Reproduces the failed HashCache cross-check (same scene, options and seed) from any folder on any machine\n"
      << "# with hpsf: $HPSF if set, else hpsf on PATH. Writes reproduced.json beside report.json.\n"
      << "cd \"$(dirname \"$0\")\" || exit 3\n"
      << "hpsf=${HPSF:-$(command -v hpsf)}\n"
      << "if [ -z \"$hpsf\" ]; then echo \"reproduce.sh: no hpsf: set HPSF=/path/to/hpsf or put hpsf on PATH\" >&2; "
         "exit 3; fi\n"
      << "echo " << Quoted(std::string("written by hpsf ") + kHpsfVersion) << " >&2\n"
      << "exec \"$hpsf\" crosscheck " << Quoted(scene) << options
      << " --repro-dir reproduced --json > reproduced.json\n";
  fs::permissions(fs::path(dir) / "reproduce.sh", fs::perms::owner_exec, fs::perm_options::add);
}

}  // namespace hpsf
