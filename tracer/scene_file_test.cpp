#include "tracer/scene_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"

namespace hpsf {
namespace {

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / ("hpsf_scene_test_" + name);
  std::ofstream(path) << text;
  return path.string();
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kValidHeader = R"("hpsf_scene": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y_degrees": 40},
  "materials": [{"name": "grey", "albedo": [0.5, 0.5, 0.5]}])";

TEST(SceneFile, BuiltinScenesLoad) {
  for (const std::string& name : BuiltinSceneNames()) {
    const Scene s = LoadScene(name);
    EXPECT_FALSE(s.triangles.empty()) << name;
    EXPECT_EQ(s.name, name);
  }
  EXPECT_EQ(LoadScene("cornell").triangles.size(), 32u);
  EXPECT_NEAR(LoadScene("cornell-far-1e7").camera.position.x, 1e7 + 278, 1e-6);
}

TEST(SceneFile, MalformedJsonNamesTheFileAndByte) {
  const std::string path = WriteTemp("malformed.json", "{\"hpsf_scene\": 1, \"camera\": ");
  const std::string error = ErrorOf([&] { LoadScene(path); });
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("not valid JSON at byte"), std::string::npos) << error;
}

TEST(SceneFile, ErrorsNameTheJsonPointer) {
  const std::string bad_material = std::string("{") + kValidHeader + R"(, "shapes": [{"material": "gold", "box": {"min": [0,0,0], "max": [1,1,1]}}]})";
  EXPECT_NE(ErrorOf([&] { ParseScene(bad_material, "s.json", "."); }).find("s.json: /shapes/0/material: no material named 'gold'"),
            std::string::npos);
  const std::string bad_point = std::string("{") + kValidHeader + R"(, "shapes": [{"material": "grey", "quad": [[0,0,0],[1,0,0],[1,1,0],[0,"x",0]]}]})";
  EXPECT_NE(ErrorOf([&] { ParseScene(bad_point, "s.json", "."); }).find("/shapes/0/quad/3/1: expected a number"), std::string::npos);
  const std::string bad_albedo = R"({"hpsf_scene": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y_degrees": 40},
    "materials": [{"name": "grey", "albedo": [0.5, 1.5, 0.5]}], "shapes": []})";
  EXPECT_NE(ErrorOf([&] { ParseScene(bad_albedo, "s.json", "."); }).find("/materials/0/albedo/1: must lie in [0"), std::string::npos);
}

TEST(SceneFile, MissingMeshAndNanVerticesAreNamed) {
  const std::string missing = std::string("{") + kValidHeader + R"(, "shapes": [{"material": "grey", "mesh": "no_such_mesh.obj"}]})";
  EXPECT_NE(ErrorOf([&] { ParseScene(missing, "s.json", "/tmp"); }).find("/tmp/no_such_mesh.obj: cannot open the mesh file"),
            std::string::npos);
  const std::string obj = WriteTemp("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  const std::string with_nan = std::string("{") + kValidHeader + R"(, "shapes": [{"material": "grey", "mesh": ")" + obj + R"("}]})";
  const std::string error = ErrorOf([&] { ParseScene(with_nan, "s.json", "."); });
  EXPECT_NE(error.find(obj + ":3: vertex coordinate 2 is not a finite number: 'nan'"), std::string::npos) << error;
}

TEST(SceneFile, ObjMeshesBecomeTriangles) {
  const std::string obj = WriteTemp("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const std::string text = std::string("{") + kValidHeader + R"(, "shapes": [{"material": "grey", "mesh": ")" + obj +
                           R"(", "scale": 2, "translate": [1, 0, 0]}]})";
  const Scene s = ParseScene(text, "s.json", ".");
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0].p1, glm::vec3(3.0f, 0.0f, 0.0f));
}

TEST(SceneFile, UnknownNameIsNeitherFileNorBuiltin) {
  EXPECT_NE(ErrorOf([] { LoadScene("no-such-scene"); }).find("not a built-in scene (cornell, furnace"), std::string::npos);
}

}  // namespace
}  // namespace hpsf
