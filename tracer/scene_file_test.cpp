#include "tracer/scene_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tracer/obj_mesh.h"

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

const char* kValidHeader =
    R"("hpsf_scene": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y_degrees": 40},
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
  const std::string bad_material = std::string("{") + kValidHeader +
                                   R"(, "shapes": [{"material": "gold", "box": {"min": [0,0,0], "max": [1,1,1]}}]})";
  EXPECT_NE(ErrorOf([&] {
              ParseScene(bad_material, "s.json", ".");
            }).find("s.json: /shapes/0/material: no material named 'gold'"),
            std::string::npos);
  const std::string bad_point = std::string("{") + kValidHeader +
                                R"(, "shapes": [{"material": "grey", "quad": [[0,0,0],[1,0,0],[1,1,0],[0,"x",0]]}]})";
  EXPECT_NE(ErrorOf([&] { ParseScene(bad_point, "s.json", "."); }).find("/shapes/0/quad/3/1: expected a number"),
            std::string::npos);
  const std::string bad_albedo =
      R"({"hpsf_scene": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y_degrees": 40},
    "materials": [{"name": "grey", "albedo": [0.5, 1.5, 0.5]}], "shapes": []})";
  EXPECT_NE(ErrorOf([&] { ParseScene(bad_albedo, "s.json", "."); }).find("/materials/0/albedo/1: must lie in [0"),
            std::string::npos);
}

TEST(SceneFile, MissingMeshAndNanVerticesAreNamed) {
  const std::string missing =
      std::string("{") + kValidHeader + R"(, "shapes": [{"material": "grey", "mesh": "no_such_mesh.obj"}]})";
  EXPECT_NE(
      ErrorOf([&] { ParseScene(missing, "s.json", "/tmp"); }).find("/tmp/no_such_mesh.obj: cannot open the mesh file"),
      std::string::npos);
  const std::string obj = WriteTemp("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  const std::string with_nan =
      std::string("{") + kValidHeader + R"(, "shapes": [{"material": "grey", "mesh": ")" + obj + R"("}]})";
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

// Found by fuzz_scene: a number beyond double's range made the JSON parser throw out_of_range, not bad input.
TEST(SceneFile, NumberBeyondDoubleRangeIsAnInputError) {
  const std::string text = std::string("{").append(kValidHeader).append(R"(, "sky": [1e400, 0, 0], "shapes": []})");
  EXPECT_NE(ErrorOf([&] { ParseScene(text, "s.json", "."); }).find("s.json: not valid JSON: "), std::string::npos);
}

// Found by fuzz_scene: a name that is not a string escaped as nlohmann's type_error instead of bad input.
TEST(SceneFile, NonStringNameIsAnInputError) {
  const std::string text = std::string("{").append(kValidHeader).append(R"(, "name": 5,
    "shapes": [{"material": "grey", "box": {"min": [0, 0, 0], "max": [1, 1, 1]}}]})");
  EXPECT_NE(ErrorOf([&] { ParseScene(text, "s.json", "."); }).find("s.json: /name: expected a string"),
            std::string::npos);
}

// Found writing fuzz_scene's scene check (its search did not reach it in 180 s): a mesh's scale could carry finite
// OBJ coordinates past float range, to infinite triangles.
TEST(SceneFile, MeshScaledBeyondFloatRangeIsAnInputError) {
  const std::string obj = WriteTemp("scaled.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string text = std::string("{")
                               .append(kValidHeader)
                               .append(R"(, "shapes": [{"material": "grey", "mesh": ")")
                               .append(obj)
                               .append(R"(", "scale": 1e300}]})");
  EXPECT_NE(ErrorOf([&] { ParseScene(text, "s.json", "."); }).find("/shapes/0/scale: expected a scale and translation"),
            std::string::npos);
}

// Found by fuzz_obj (UBSan): tinyobjloader converts a skin weight's joint id to int unchecked.
TEST(SceneFile, ObjSkinWeightBeyondIntRangeIsAnInputError) {
  const std::string obj = WriteTemp("skin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 0 1e38 1\nf 1 2 3\n");
  EXPECT_NE(ErrorOf([&] { LoadObjTriangles(obj); }).find("skin.obj:4: skin weight value '1e38' lies beyond"),
            std::string::npos);
  // Found by fuzz_obj in CI: tinyobjloader reads joint ids as floats, and 2147483647 rounds to 2^31.
  const std::string rounded = WriteTemp("skin_rounded.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 0 2147483647 1\nf 1 2 3\n");
  EXPECT_NE(ErrorOf([&] {
              LoadObjTriangles(rounded);
            }).find("skin_rounded.obj:4: skin weight value '2147483647' lies beyond"),
            std::string::npos);
}

// Found by fuzz_obj in CI (UBSan): tinyobjloader's number parser reads 00e3848364 as 0 times 10^3848364, NaN, and
// converts it to an int. Skin weights never reach it now; the mesh loads as if the line were not there (the asan
// run's float-cast-overflow check sees the conversion if one does).
TEST(SceneFile, ObjSkinWeightsAreIgnoredWhateverTinyobjloaderWouldReadInThem) {
  const std::string obj =
      WriteTemp("skin_nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 0 00e3848364 1\r vw 0 0 1\nf 1 2 3\n");
  EXPECT_EQ(LoadObjTriangles(obj).size(), 1u);
}

// Found by fuzz_obj (UBSan): a face index past 2^31 / 3 overflowed int in the missing-vertex check.
TEST(SceneFile, ObjFaceIndexBeyondIntRangeIsAMissingVertex) {
  const std::string obj = WriteTemp("big_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1908428344\n");
  EXPECT_NE(ErrorOf([&] { LoadObjTriangles(obj); }).find("face 1 of shape '' refers to a missing vertex"),
            std::string::npos);
}

// A lone carriage return ends a line for tinyobjloader, so the vertex check must see the line it starts.
TEST(SceneFile, ObjNanVertexAfterCarriageReturnIsNamed) {
  const std::string obj = WriteTemp("cr.obj", "v 0 0 0\rv 1 nan 0\r\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(ErrorOf([&] { LoadObjTriangles(obj); }).find("cr.obj:2: vertex coordinate 2 is not a finite number"),
            std::string::npos);
}

TEST(SceneFile, UnknownNameIsNeitherFileNorBuiltin) {
  EXPECT_NE(ErrorOf([] { LoadScene("no-such-scene"); }).find("not a built-in scene (cornell, furnace"),
            std::string::npos);
}

}  // namespace
}  // namespace hpsf
