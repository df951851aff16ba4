// fuzz_scene: scene JSON through tracer/scene_file.h's ParseScene, with an OBJ beside it. The input is the JSON,
// then optionally a line "--- mesh.obj ---" and the OBJ's text, written as mesh.obj in the scratch directory that
// relative mesh paths resolve against. Every input is a scene or an hpsf::InputError; a bug is a crash, a hang,
// a sanitizer report, any other exception, or a scene with a non-finite coordinate (or one beyond float range)
// in its camera or triangles, at any frame of its animation. Inputs naming an absolute path or ".." are skipped: they
// would read the machine's files (/dev/zero never ends), which hpsf rightly allows.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "tools/fuzz/scratch_dir.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

constexpr std::size_t kMaxInputBytes = 1 << 16;
constexpr std::string_view kMeshSeparator = "\n--- mesh.obj ---\n";

// Whether any string in the JSON could name a file outside the scratch directory.
bool NamesOutsideFiles(const nlohmann::json& j) {
  if (j.is_string()) {
    const std::string& s = j.get_ref<const std::string&>();
    return std::filesystem::path(s).is_absolute() || s.find("..") != std::string::npos;
  }
  if (j.is_structured()) {
    for (const nlohmann::json& child : j) {
      if (NamesOutsideFiles(child)) return true;
    }
  }
  return false;
}

bool Finite(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
bool WithinFloatRange(const glm::vec3& p) {
  return std::abs(p.x) < 3e38f && std::abs(p.y) < 3e38f && std::abs(p.z) < 3e38f;
}

void CheckScene(const Scene& scene) {
  bool ok = Finite(scene.camera.position) && Finite(scene.camera.look_at) && Finite(scene.camera.up);
  for (const Triangle& t : scene.triangles)
    ok = ok && WithinFloatRange(t.p0) && WithinFloatRange(t.p1) && WithinFloatRange(t.p2);
  if (!ok) {
    std::fprintf(stderr, "fuzz_scene: a scene with a non-finite or out-of-range coordinate was accepted\n");
    std::abort();
  }
}

}  // namespace
}  // namespace hpsf

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hpsf;
  if (size > kMaxInputBytes) return 0;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t separator = input.find(kMeshSeparator);
  const std::string json_text(input.substr(0, separator));
  const std::string_view obj_text =
      separator == std::string_view::npos ? std::string_view() : input.substr(separator + kMeshSeparator.size());
  const nlohmann::json parsed = nlohmann::json::parse(json_text, nullptr, false);
  if (!parsed.is_discarded() && NamesOutsideFiles(parsed)) return 0;
  Scratch().Write("mesh.obj", obj_text);
  try {
    const Scene scene = ParseScene(json_text, "fuzz.json", Scratch().path().string());
    CheckScene(scene);
    // An animated scene at its keys, around them and far after the last: every frame a valid scene too.
    std::vector<std::uint32_t> frames = {0, 0xffffffffu};
    for (const CameraKey& k : scene.animation.camera) frames.insert(frames.end(), {k.frame, k.frame + 1});
    for (const ShapeAnimation& a : scene.animation.shapes) {
      for (const ShapeKey& k : a.keys) frames.insert(frames.end(), {k.frame, k.frame + 1});
    }
    if (!scene.animation.Static()) {
      for (std::uint32_t frame : frames) CheckScene(scene.AtFrame(frame));
    }
  } catch (const InputError&) {
  }
  return 0;
}
