#include "tracer/scene_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "tracer/builtin_scene_data.h"
#include "tracer/obj_mesh.h"

namespace hpsf {
namespace {

using nlohmann::json;

// Below float's largest value (3.4e38) with a margin, so a point converts to a finite float.
bool WithinFloatRange(const glm::dvec3& p) {
  return std::abs(p.x) < 3e38 && std::abs(p.y) < 3e38 && std::abs(p.z) < 3e38;
}

class SceneParser {
 public:
  SceneParser(std::string source, std::string directory)
      : source_(std::move(source)), directory_(std::move(directory)) {}

  Scene Parse(const std::string& text) {
    json root;
    try {
      root = json::parse(text);
    } catch (const json::parse_error& e) {
      throw InputError(source_ + ": not valid JSON at byte " + std::to_string(e.byte) + ": " + e.what());
    } catch (const json::exception& e) {  // out_of_range.406: a number beyond double's range, e.g. 1e400
      throw InputError(source_ + ": not valid JSON: " + e.what());
    }
    Expect(root.is_object(), "", "a JSON object");
    Expect(root.contains("hpsf_scene") && root["hpsf_scene"] == 1, "/hpsf_scene", "the format version 1");
    Scene scene;
    scene.name = std::filesystem::path(source_).stem().string();
    if (root.contains("name")) {
      Expect(root["name"].is_string(), "/name", "a string");
      scene.name = root["name"].get<std::string>();
    }
    scene.camera = ParseCamera(Member(root, "", "camera"));
    if (root.contains("sky")) scene.sky = Color(root["sky"], "/sky", 0.0f, INFINITY);
    const json& materials = Member(root, "", "materials");
    Expect(materials.is_array() && !materials.empty(), "/materials", "a non-empty array");
    for (std::size_t i = 0; i < materials.size(); ++i)
      scene.materials.push_back(ParseMaterial(materials[i], "/materials/" + std::to_string(i)));
    std::map<std::string, std::uint32_t> by_name;
    for (std::uint32_t i = 0; i < scene.materials.size(); ++i) {
      const std::string& name = scene.materials[i].name;
      if (!by_name.emplace(name, i).second)
        Fail("/materials/" + std::to_string(i) + "/name", "duplicate material '" + name + "'");
    }
    const json& shapes = Member(root, "", "shapes");
    Expect(shapes.is_array() && !shapes.empty(), "/shapes", "a non-empty array");
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      const std::string pointer = "/shapes/" + std::to_string(i);
      const std::uint32_t first = std::uint32_t(scene.triangles.size());
      ParseShape(shapes[i], pointer, by_name, scene);
      if (shapes[i].contains("name")) {
        Expect(shapes[i]["name"].is_string(), pointer + "/name", "a string");
        const std::string name = shapes[i]["name"].get<std::string>();
        for (const NamedShape& other : scene.shapes) {
          if (other.name == name) Fail(pointer + "/name", "duplicate shape name '" + name + "'");
        }
        scene.shapes.push_back({name, first, std::uint32_t(scene.triangles.size()) - first});
      }
    }
    if (root.contains("animation")) scene.animation = ParseAnimation(root["animation"], scene);
    return scene;
  }

 private:
  [[noreturn]] void Fail(const std::string& pointer, const std::string& problem) const {
    throw InputError(source_ + ": " + (pointer.empty() ? "/" : pointer) + ": " + problem);
  }
  void Expect(bool ok, const std::string& pointer, const std::string& expected) const {
    if (!ok) Fail(pointer, "expected " + expected);
  }
  const json& Member(const json& object, const std::string& pointer, const char* key) const {
    Expect(object.is_object() && object.contains(key), pointer + "/" + key, "a member '" + std::string(key) + "'");
    return object[key];
  }

  double Number(const json& value, const std::string& pointer) const {
    Expect(value.is_number(), pointer, "a number");
    const double x = value.get<double>();
    Expect(std::isfinite(x), pointer, "a finite number");
    return x;
  }
  glm::dvec3 Point(const json& value, const std::string& pointer) const {
    Expect(value.is_array() && value.size() == 3, pointer, "an array of 3 numbers");
    glm::dvec3 p;
    for (int i = 0; i < 3; ++i) p[i] = Number(value[i], pointer + "/" + std::to_string(i));
    Expect(WithinFloatRange(p), pointer, "coordinates within float range");
    return p;
  }
  glm::vec3 Color(const json& value, const std::string& pointer, float low, float high) const {
    const glm::dvec3 c = Point(value, pointer);
    for (int i = 0; i < 3; ++i) {
      if (!(c[i] >= low && c[i] <= high)) {
        Fail(pointer + "/" + std::to_string(i),
             "must lie in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
      }
    }
    return glm::vec3(c);
  }

  Camera ParseCamera(const json& j) const {
    Camera c;
    c.position = Point(Member(j, "/camera", "position"), "/camera/position");
    c.look_at = Point(Member(j, "/camera", "look_at"), "/camera/look_at");
    c.up = j.contains("up") ? Point(j["up"], "/camera/up") : glm::dvec3(0.0, 1.0, 0.0);
    c.fov_y_degrees = Number(Member(j, "/camera", "fov_y_degrees"), "/camera/fov_y_degrees");
    Expect(c.fov_y_degrees > 0.0 && c.fov_y_degrees < 180.0, "/camera/fov_y_degrees", "an angle in (0, 180) degrees");
    Expect(c.look_at != c.position, "/camera/look_at", "a point other than the camera position");
    return c;
  }

  // A keyframe's frame: an integer in [0, 2^31).
  std::uint32_t Frame(const json& key, const std::string& pointer) const {
    const double f = Number(Member(key, pointer, "frame"), pointer + "/frame");
    Expect(f >= 0.0 && f < 2147483648.0 && f == std::floor(f), pointer + "/frame",
           "a frame number, an integer in [0, 2^31)");
    return std::uint32_t(f);
  }
  template <typename Key>
  void ExpectIncreasing(const std::vector<Key>& keys, const std::string& pointer) const {
    for (std::size_t i = 1; i < keys.size(); ++i) {
      if (keys[i].frame <= keys[i - 1].frame)
        Fail(pointer + "/" + std::to_string(i) + "/frame", "frames must increase from key to key");
    }
  }
  const json& Keys(const json& value, const std::string& pointer) const {
    Expect(value.is_array() && !value.empty(), pointer, "a non-empty array of keyframes");
    return value;
  }

  // "animation": {"camera": [{"frame", "position"?, "look_at"?}...], "shapes": [{"shape": NAME, "keys":
  // [{"frame", "translate"?, "emission_scale"?}...]}...]}. What a key leaves out is the scene's own value.
  Animation ParseAnimation(const json& j, const Scene& scene) const {
    Expect(j.is_object(), "/animation", "an object");
    for (const auto& [key, value] : j.items()) {
      if (key != "camera" && key != "shapes")
        Fail("/animation/" + key, "not a member of an animation (camera, shapes)");
    }
    Animation animation;
    if (j.contains("camera")) {
      const json& keys = Keys(j["camera"], "/animation/camera");
      for (std::size_t i = 0; i < keys.size(); ++i) {
        const std::string pointer = "/animation/camera/" + std::to_string(i);
        Expect(keys[i].is_object(), pointer, "a keyframe object");
        CameraKey k{Frame(keys[i], pointer), scene.camera.position, scene.camera.look_at};
        if (keys[i].contains("position")) k.position = Point(keys[i]["position"], pointer + "/position");
        if (keys[i].contains("look_at")) k.look_at = Point(keys[i]["look_at"], pointer + "/look_at");
        Expect(k.look_at != k.position, pointer + "/look_at", "a point other than the camera position");
        animation.camera.push_back(k);
      }
      ExpectIncreasing(animation.camera, "/animation/camera");
    }
    if (j.contains("shapes")) {
      const json& shapes = j["shapes"];
      Expect(shapes.is_array(), "/animation/shapes", "an array");
      for (std::size_t s = 0; s < shapes.size(); ++s) {
        const std::string pointer = "/animation/shapes/" + std::to_string(s);
        const json& name = Member(shapes[s], pointer, "shape");
        Expect(name.is_string(), pointer + "/shape", "a shape's name");
        const auto shape = std::find_if(scene.shapes.begin(), scene.shapes.end(),
                                        [&](const NamedShape& n) { return n.name == name.get<std::string>(); });
        if (shape == scene.shapes.end()) Fail(pointer + "/shape", "no shape named '" + name.get<std::string>() + "'");
        for (const ShapeAnimation& other : animation.shapes) {
          if (other.shape == shape->name) Fail(pointer + "/shape", "'" + shape->name + "' is animated twice");
        }
        const bool emits =
            shape->triangle_count > 0 && scene.materials[scene.triangles[shape->first_triangle].material].IsEmissive();
        ShapeAnimation a{shape->name, {}};
        const json& keys = Keys(Member(shapes[s], pointer, "keys"), pointer + "/keys");
        for (std::size_t i = 0; i < keys.size(); ++i) {
          const std::string key = pointer + "/keys/" + std::to_string(i);
          Expect(keys[i].is_object(), key, "a keyframe object");
          ShapeKey k{Frame(keys[i], key), glm::dvec3(0.0), 1.0};
          if (keys[i].contains("translate")) {
            k.translate = Point(keys[i]["translate"], key + "/translate");
            // A frame between two keys lies between their positions, so checking the keys covers every frame.
            for (std::uint32_t t = shape->first_triangle; t < shape->first_triangle + shape->triangle_count; ++t) {
              const Triangle& tri = scene.triangles[t];
              for (const glm::vec3& p : {tri.p0, tri.p1, tri.p2}) {
                Expect(WithinFloatRange(glm::dvec3(p) + k.translate), key + "/translate",
                       "a translation that keeps '" + shape->name + "' within float range");
              }
            }
          }
          if (keys[i].contains("emission_scale")) {
            if (!emits) Fail(key + "/emission_scale", "'" + shape->name + "' does not emit");
            k.emission_scale = Number(keys[i]["emission_scale"], key + "/emission_scale");
            Expect(k.emission_scale >= 0.0 && k.emission_scale <= 1e6, key + "/emission_scale", "a scale in [0, 1e6]");
          }
          a.keys.push_back(k);
        }
        ExpectIncreasing(a.keys, pointer + "/keys");
        animation.shapes.push_back(a);
      }
    }
    return animation;
  }

  Material ParseMaterial(const json& j, const std::string& pointer) const {
    Material m;
    const json& name = Member(j, pointer, "name");
    Expect(name.is_string(), pointer + "/name", "a string");
    m.name = name.get<std::string>();
    m.albedo = Color(Member(j, pointer, "albedo"), pointer + "/albedo", 0.0f, 1.0f);
    if (j.contains("emission")) m.emission = Color(j["emission"], pointer + "/emission", 0.0f, 1e30f);
    return m;
  }

  void ParseShape(const json& j, const std::string& pointer, const std::map<std::string, std::uint32_t>& materials,
                  Scene& scene) const {
    Expect(j.is_object(), pointer, "a shape object");
    const json& material = Member(j, pointer, "material");
    Expect(material.is_string(), pointer + "/material", "a material name");
    auto found = materials.find(material.get<std::string>());
    if (found == materials.end())
      Fail(pointer + "/material", "no material named '" + material.get<std::string>() + "'");
    const std::uint32_t id = found->second;
    auto add = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
      scene.triangles.push_back({glm::vec3(a), glm::vec3(b), glm::vec3(c), id});
    };

    if (j.contains("quad")) {
      const json& q = j["quad"];
      Expect(q.is_array() && q.size() == 4, pointer + "/quad", "4 corners");
      glm::dvec3 p[4];
      for (int i = 0; i < 4; ++i) p[i] = Point(q[i], pointer + "/quad/" + std::to_string(i));
      add(p[0], p[1], p[2]);
      add(p[0], p[2], p[3]);
    } else if (j.contains("box")) {
      const glm::dvec3 lo = Point(Member(j["box"], pointer + "/box", "min"), pointer + "/box/min");
      const glm::dvec3 hi = Point(Member(j["box"], pointer + "/box", "max"), pointer + "/box/max");
      Expect(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z, pointer + "/box", "min below max on every axis");
      auto corner = [&](int i) { return glm::dvec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
      const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
      for (const auto& f : faces) {
        add(corner(f[0]), corner(f[1]), corner(f[2]));
        add(corner(f[0]), corner(f[2]), corner(f[3]));
      }
    } else if (j.contains("mesh")) {
      Expect(j["mesh"].is_string(), pointer + "/mesh", "an OBJ file path");
      std::filesystem::path path = j["mesh"].get<std::string>();
      if (path.is_relative()) path = std::filesystem::path(directory_) / path;
      const double scale = j.contains("scale") ? Number(j["scale"], pointer + "/scale") : 1.0;
      const glm::dvec3 translate =
          j.contains("translate") ? Point(j["translate"], pointer + "/translate") : glm::dvec3(0.0);
      for (const ObjTriangle& t : LoadObjTriangles(path.string())) {
        glm::dvec3 p[3];
        for (int i = 0; i < 3; ++i) {
          p[i] = t.p[i] * scale + translate;
          Expect(WithinFloatRange(p[i]), pointer + "/scale",
                 "a scale and translation that keep the mesh within float range");
        }
        add(p[0], p[1], p[2]);
      }
    } else {
      Fail(pointer, "expected a 'quad', 'box' or 'mesh' member");
    }
  }

  std::string source_;
  std::string directory_;
};

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The hard cases are the Cornell box moved, scaled or recoloured: the same light transport, other numbers.
Scene Cornell() { return ParseScene(kCornellSceneJson, "builtin:cornell", "."); }

}  // namespace

Scene ParseScene(const std::string& json_text, const std::string& source, const std::string& directory) {
  return SceneParser(source, directory).Parse(json_text);
}

Scene LoadSceneFile(const std::string& path) {
  const std::string directory = std::filesystem::path(path).parent_path().string();
  return ParseScene(ReadFile(path), path, directory.empty() ? "." : directory);
}

const std::vector<std::string>& BuiltinSceneNames() {
  static const std::vector<std::string> names = {"cornell",         "furnace",      "cornell-far-1e5",
                                                 "cornell-far-1e7", "cornell-tiny", "cornell-zero-red"};
  return names;
}

Scene LoadScene(const std::string& name) {
  if (name == "cornell") return Cornell();
  if (name == "furnace") return ParseScene(kFurnaceSceneJson, "builtin:furnace", ".");
  if (name == "cornell-far-1e5" || name == "cornell-far-1e7") {
    Scene scene = Cornell();
    const double offset = name == "cornell-far-1e5" ? 1e5 : 1e7;
    scene.Transform(1.0, glm::dvec3(offset, offset, offset));
    scene.name = name;
    return scene;
  }
  if (name == "cornell-tiny") {
    Scene scene = Cornell();
    scene.Transform(1e-4, glm::dvec3(0.0));
    scene.name = name;
    return scene;
  }
  if (name == "cornell-zero-red") {
    Scene scene = Cornell();
    for (Material& m : scene.materials) m.albedo.r = 0.0f;
    scene.name = name;
    return scene;
  }
  if (!std::filesystem::exists(name)) {
    std::string known;
    for (const std::string& n : BuiltinSceneNames()) known += (known.empty() ? "" : ", ") + n;
    throw InputError(name + ": no such scene file, and not a built-in scene (" + known + ")");
  }
  return LoadSceneFile(name);
}

}  // namespace hpsf
