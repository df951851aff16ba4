#include "tools/hpsf/reference_cache.h"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/fnv1a.h"
#include "tools/hpsf/image_file.h"
#include "tools/hpsf/seconds_since.h"
#include "tracer/scene_digest.h"

namespace hpsf {
namespace {

std::string Hex(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace

std::string DefaultReferenceCache() {
  if (const char* explicit_folder = std::getenv("HPSF_CACHE"); explicit_folder && *explicit_folder) {
    return explicit_folder;
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/hpsf/references";
  if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/hpsf/references";
  return ".hpsf-cache/references";
}

CachedReference ReferenceCacheEntry(const std::string& folder, const std::string& description) {
  const std::string key = Hex(Fnv1a(description.data(), description.size()));
  const std::filesystem::path base = std::filesystem::path(folder) / key;
  return {key, base.string() + ".exr", base.string() + ".json"};
}

std::optional<std::string> FindCachedReference(const CachedReference& entry, const std::string& description) {
  std::ifstream in(entry.sidecar);
  if (!in || !std::filesystem::exists(entry.image)) return std::nullopt;
  const nlohmann::json sidecar = nlohmann::json::parse(in, nullptr, false);
  if (sidecar.is_discarded() || sidecar.value("description", "") != description) return std::nullopt;
  return entry.image;
}

void WriteReferenceSidecar(const CachedReference& entry, const std::string& description, double seconds) {
  const nlohmann::json sidecar = {{"version", 1}, {"description", description}, {"seconds", seconds}};
  const std::string temporary = entry.sidecar + ".partial";
  {
    std::ofstream out(temporary);
    out << sidecar.dump(2) << "\n";
    if (!out) throw InputError(entry.sidecar + ": cannot write the cache's sidecar");
  }
  std::filesystem::rename(temporary, entry.sidecar);
}

ReferenceImage GetReferenceImage(const Scene& scene, const std::string& scene_name, const ReferenceRequest& request,
                                 const std::string& folder, bool refresh,
                                 const std::function<void(std::uint32_t, std::uint32_t)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  ReferenceImage result;
  result.description = request.Description(SceneDigest(scene, request.trace.frame));
  result.entry = ReferenceCacheEntry(folder, result.description);
  result.cached = !refresh && FindCachedReference(result.entry, result.description).has_value();
  if (!result.cached) {
    const ConvergedImage image = RenderConverged(scene, request, progress);
    std::filesystem::create_directories(folder);
    WriteImageFiles(result.entry.image, image.mean,
                    {{"scene", scene_name},
                     {"backend", "path tracing"},
                     {"spp", std::to_string(request.samples_per_pixel)},
                     {"seed", std::to_string(request.trace.seed)},
                     {"frame", std::to_string(request.trace.frame)},
                     {"tracer_version", std::to_string(kTracerVersion)},
                     {"reference", result.description}},
                    std::vector<ImageLayer>{{"variance", &image.variance}});
    WriteReferenceSidecar(result.entry, result.description, SecondsSince(start));
  }
  result.seconds = SecondsSince(start);
  return result;
}

}  // namespace hpsf
