// Where `hpsf reference` keeps its converged images: one EXR (with its variance channels and PNG preview) and one
// JSON sidecar per request, named by a 64-bit FNV-1a hash of the request's description (the scene's digest, the
// tracer version, size, samples, seed, frame, depth). A cached image is used only when its sidecar holds the very
// same description, so neither a hash collision nor a changed scene or tracer can hand back a stale image. The
// folder: --cache, else $HPSF_CACHE, else $XDG_CACHE_HOME/hpsf/references, else ~/.cache/hpsf/references.
#ifndef HPSF_TOOLS_HPSF_REFERENCE_CACHE_H
#define HPSF_TOOLS_HPSF_REFERENCE_CACHE_H

#include <optional>
#include <string>

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

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_REFERENCE_CACHE_H
