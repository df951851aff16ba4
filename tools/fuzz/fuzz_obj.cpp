// fuzz_obj: OBJ text through the mesh loader (tracer/obj_mesh.h: its own vertex-line check, then tinyobjloader,
// compiled instrumented in this build). Every input is a list of triangles or an hpsf::InputError naming the
// file; a bug is a crash, a hang, a sanitizer report, any other exception, or a triangle with a non-finite
// corner (the loader promises finite coordinates).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "core/error.h"
#include "tools/fuzz/scratch_dir.h"
#include "tracer/obj_mesh.h"

namespace {

constexpr std::size_t kMaxInputBytes = 1 << 16;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInputBytes) return 0;
  const std::string path =
      hpsf::Scratch().Write("mesh.obj", std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    for (const hpsf::ObjTriangle& t : hpsf::LoadObjTriangles(path)) {
      for (const glm::dvec3& p : t.p) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
          std::fprintf(stderr, "fuzz_obj: a triangle with a non-finite corner was accepted\n");
          std::abort();
        }
      }
    }
  } catch (const hpsf::InputError&) {
  }
  return 0;
}
