// Where `hpsf reference` keeps its converged images: one EXR (with its variance channels and PNG preview) and one
// JSON sidecar per request, named by a 64-bit FNV-1a hash of the request's description (the scene's digest, the
// tracer version, size, samples, seed, frame, depth). A cached image is used only when its sidecar holds the very
// same description, so neither a hash collision nor a changed scene or tracer can hand back a stale image. The
// folder: --cache, else $HPSF_CACHE, else $XDG_CACHE_HOME/hpsf/references, else ~/.cache/hpsf/references.
#ifndef HPSF_TOOLS_HPSF_REFERENCE_CACHE_H
#define HPSF_TOOLS_HPSF_REFERENCE_CACHE_H

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "tools/hpsf/converged_reference.h"
#include "tracer/scene.h"

namespace hpsf {

std::string DefaultReferenceCache();

struct CachedReference {
  std::string key;      // 16 hex digits
  std::string image;    // DIR/KEY.exr
  std::string sidecar;  // DIR/KEY.json
};

CachedReference ReferenceCacheEntry(const std::string& folder, const std::string& description);

// The entry's image when it exists and its sidecar holds `description`.
std::optional<std::string> FindCachedReference(const CachedReference& entry, const std::string& description);

// Writes the sidecar after the image is in place (so a sidecar always names a whole image).
void WriteReferenceSidecar(const CachedReference& entry, const std::string& description, double seconds);

struct ReferenceImage {
  CachedReference entry;
  std::string description;
  bool cached = false;  // read from the cache, not rendered
  double seconds = 0.0;
};

// The converged image of `scene` for `request` (tools/hpsf/converged_reference.h): read from the cache in `folder`
// when it holds it (and `refresh` is false), else rendered and stored there. `scene_name` goes into the EXR's
// metadata only; progress(done, total) after each pass of a render.
ReferenceImage GetReferenceImage(const Scene& scene, const std::string& scene_name, const ReferenceRequest& request,
                                 const std::string& folder, bool refresh,
                                 const std::function<void(std::uint32_t, std::uint32_t)>& progress = {});

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_REFERENCE_CACHE_H
