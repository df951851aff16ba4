// Keyframes: interpolation, the scene at a frame, the scene file's animation member and its errors, and the
// tracer tracing the scene at its frame.
#include "tracer/animation.h"

#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tracer/path_tracer.h"
#include "tracer/scene.h"
#include "tracer/scene_file.h"

namespace hpsf {
namespace {

std::string ErrorOf(const std::string& json) {
  try {
    ParseScene(json, "test.json", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// A camera, a grey floor, a named emitting quad "lamp" and a named box "block", with the animation given.
std::string SceneJson(const std::string& animation) {
  return R"({"hpsf_scene": 1, "camera": {"position": [0, 2, -6], "look_at": [0, 0, 0], "fov_y_degrees": 50},
    "materials": [{"name": "grey", "albedo": [0.5, 0.5, 0.5]},
                  {"name": "lamp", "albedo": [0, 0, 0], "emission": [4, 4, 4]}],
    "shapes": [{"material": "grey", "quad": [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]},
               {"name": "lamp", "material": "lamp", "quad": [[-1, 3, -1], [1, 3, -1], [1, 3, 1], [-1, 3, 1]]},
               {"name": "block", "material": "grey", "box": {"min": [-0.5, 0, -0.5], "max": [0.5, 1, 0.5]}}])" +
         std::string(animation.empty() ? "" : ", \"animation\": " + animation) + "}";
}

TEST(Animation, KeysAreExactAndBetweenThemLinearThenHeld) {
  const std::vector<ShapeKey> keys = {{4, {0.0, 0.0, 0.0}, 1.0}, {12, {8.0, -4.0, 2.0}, 0.0}};
  EXPECT_EQ(ShapeAt(keys, 0).translate, glm::dvec3(0.0));  // held before the first key
  EXPECT_EQ(ShapeAt(keys, 4).translate, glm::dvec3(0.0));
  EXPECT_EQ(ShapeAt(keys, 8).translate, glm::dvec3(4.0, -2.0, 1.0));
  EXPECT_EQ(ShapeAt(keys, 8).emission_scale, 0.5);
  EXPECT_EQ(ShapeAt(keys, 10).translate, glm::dvec3(6.0, -3.0, 1.5));
  EXPECT_EQ(ShapeAt(keys, 12).translate, glm::dvec3(8.0, -4.0, 2.0));
  EXPECT_EQ(ShapeAt(keys, 4000000000u).translate, glm::dvec3(8.0, -4.0, 2.0));  // held after the last
  EXPECT_EQ(ShapeAt(keys, 4000000000u).emission_scale, 0.0);

  const std::vector<CameraKey> camera = {{0, {0.0, 0.0, -10.0}, {0.0, 0.0, 0.0}},
                                         {2, {2.0, 0.0, -10.0}, {2.0, 0.0, 0.0}},
                                         {6, {2.0, 4.0, -10.0}, {2.0, 0.0, 0.0}}};
  EXPECT_EQ(CameraAt(camera, 1).position, glm::dvec3(1.0, 0.0, -10.0));
  EXPECT_EQ(CameraAt(camera, 2).position, glm::dvec3(2.0, 0.0, -10.0));
  EXPECT_EQ(CameraAt(camera, 5).position, glm::dvec3(2.0, 3.0, -10.0));
  EXPECT_EQ(CameraAt(camera, 5).look_at, glm::dvec3(2.0, 0.0, 0.0));
}

TEST(Animation, AStaticSceneIsTheSameAtEveryFrame) {
  const Scene scene = ParseScene(SceneJson(""), "test.json", ".");
  ASSERT_TRUE(scene.animation.Static());
  ASSERT_EQ(scene.shapes.size(), 2u);
  for (std::uint32_t frame : {0u, 1u, 1000u}) {
    const Scene at = scene.AtFrame(frame);
    EXPECT_EQ(at.camera.position, scene.camera.position);
    ASSERT_EQ(at.triangles.size(), scene.triangles.size());
    for (std::size_t i = 0; i < at.triangles.size(); ++i) {
      EXPECT_EQ(at.triangles[i].p0, scene.triangles[i].p0);
      EXPECT_EQ(at.triangles[i].material, scene.triangles[i].material);
    }
  }
}

TEST(Animation, TheSceneAtAFrameMovesOnlyTheAnimatedShapesAndScalesAnEmittersCopy) {
  const Scene scene = ParseScene(SceneJson(R"({"camera": [{"frame": 0}, {"frame": 4, "position": [4, 2, -6]}],
      "shapes": [{"shape": "block", "keys": [{"frame": 0}, {"frame": 4, "translate": [2, 0, 0]}]},
                 {"shape": "lamp", "keys": [{"frame": 2, "emission_scale": 1}, {"frame": 6, "emission_scale": 0}]}]})"),
                                 "test.json", ".");
  ASSERT_EQ(scene.animation.shapes.size(), 2u);
  const NamedShape& block = scene.shapes[1];
  ASSERT_EQ(block.name, "block");
  ASSERT_EQ(block.triangle_count, 12u);

  const Scene frame2 = scene.AtFrame(2);
  EXPECT_EQ(frame2.camera.position, glm::dvec3(2.0, 2.0, -6.0));
  EXPECT_EQ(frame2.camera.look_at, scene.camera.look_at);  // a key without look_at keeps the scene's
  for (std::uint32_t i = 0; i < scene.triangles.size(); ++i) {
    const bool moved = i >= block.first_triangle && i < block.first_triangle + block.triangle_count;
    EXPECT_EQ(frame2.triangles[i].p1, scene.triangles[i].p1 + (moved ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f)))
        << i;
  }
  EXPECT_EQ(frame2.materials.size(), scene.materials.size());  // the lamp at scale 1 keeps its material

  const Scene frame5 = scene.AtFrame(5);
  ASSERT_EQ(frame5.materials.size(), scene.materials.size() + 1);
  const Material& dimmed = frame5.materials.back();
  EXPECT_EQ(dimmed.name, "lamp@lamp");
  EXPECT_EQ(dimmed.emission, glm::vec3(1.0f));  // 4 * 0.25
  const NamedShape& lamp = scene.shapes[0];
  EXPECT_EQ(frame5.triangles[lamp.first_triangle].material, frame5.materials.size() - 1);
  EXPECT_EQ(scene.materials[1].emission, glm::vec3(4.0f));  // the scene itself is unchanged
}

TEST(Animation, BadKeyframesAreInputErrorsNamingThePlace) {
  EXPECT_NE(ErrorOf(SceneJson(R"({"shapes": [{"shape": "nothing", "keys": [{"frame": 0}]}]})"))
                .find("test.json: /animation/shapes/0/shape: no shape named 'nothing'"),
            std::string::npos);
  EXPECT_NE(ErrorOf(SceneJson(R"({"camera": [{"frame": 3}, {"frame": 3}]})"))
                .find("/animation/camera/1/frame: frames must increase"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf(SceneJson(R"({"camera": [{"frame": 1.5}]})")).find("/animation/camera/0/frame: expected a frame number"),
      std::string::npos);
  EXPECT_NE(ErrorOf(SceneJson(R"({"camera": [{"frame": -1}]})")).find("/animation/camera/0/frame"), std::string::npos);
  EXPECT_NE(ErrorOf(SceneJson(R"({"camera": [{"frame": 0, "position": [0, 0, 0]}]})"))
                .find("/animation/camera/0/look_at: expected a point other than the camera position"),
            std::string::npos);
  EXPECT_NE(ErrorOf(SceneJson(R"({"shapes": [{"shape": "block", "keys": [{"frame": 0, "emission_scale": 2}]}]})"))
                .find("/animation/shapes/0/keys/0/emission_scale: 'block' does not emit"),
            std::string::npos);
  EXPECT_NE(ErrorOf(SceneJson(R"({"shapes": [{"shape": "lamp", "keys": [{"frame": 0, "emission_scale": -1}]}]})"))
                .find("/animation/shapes/0/keys/0/emission_scale: expected a scale in [0, 1e6]"),
            std::string::npos);
  EXPECT_NE(ErrorOf(SceneJson(R"({"shapes": [{"shape": "lamp", "keys": []}]})"))
                .find("/animation/shapes/0/keys: expected a non-empty"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf(
          SceneJson(
              R"({"shapes": [{"shape": "lamp", "keys": [{"frame": 0}]}, {"shape": "lamp", "keys": [{"frame": 0}]}]})"))
          .find("/animation/shapes/1/shape: 'lamp' is animated twice"),
      std::string::npos);
  // The block and its translation are each within float range; their sum is not (fuzz_scene checks every
  // frame's triangles).
  std::string far = SceneJson(R"({"shapes": [{"shape": "block", "keys": [{"frame": 0, "translate": [2e38, 0, 0]}]}]})");
  far.replace(far.find("[-0.5, 0, -0.5]"), 15, "[2e38, 0, 0]");
  far.replace(far.find("[0.5, 1, 0.5]"), 13, "[2.1e38, 1, 1]");
  EXPECT_NE(ErrorOf(far).find(
                "/animation/shapes/0/keys/0/translate: expected a translation that keeps 'block' within float range"),
            std::string::npos);
  EXPECT_NE(ErrorOf(SceneJson(R"({"lights": []})")).find("/animation/lights: not a member of an animation"),
            std::string::npos);
  EXPECT_NE(ErrorOf(SceneJson("[]")).find("/animation: expected an object"), std::string::npos);
  std::string twice = SceneJson("");
  twice.replace(twice.find("\"name\": \"block\""), 15, "\"name\": \"lamp\"");
  EXPECT_NE(ErrorOf(twice).find("/shapes/2/name: duplicate shape name 'lamp'"), std::string::npos);
}

// The tracer traces the scene at its options' frame: a lamp scaled to 0 at frame 1 leaves no light at all,
// while frame 0 of the same scene gives what the static scene gives, bit for bit.
TEST(Animation, TheTracerTracesTheSceneAtItsFrame) {
  const Scene animated = ParseScene(
      SceneJson(R"({"shapes": [{"shape": "lamp", "keys": [{"frame": 0}, {"frame": 1, "emission_scale": 0}]}]})"),
      "test.json", ".");
  const Scene still = ParseScene(SceneJson(""), "test.json", ".");
  TraceOptions options;
  options.width = 16;
  options.height = 12;
  options.samples_per_pixel = 2;
  const RecordBatch frame0 = TraceRecords(animated, options).batch;
  const RecordBatch reference = TraceRecords(still, options).batch;
  ASSERT_EQ(frame0.records.size(), reference.records.size());
  double light = 0.0;
  for (std::size_t i = 0; i < frame0.records.size(); ++i) {
    EXPECT_EQ(std::memcmp(&frame0.records[i], &reference.records[i], sizeof(Record)), 0) << "record " << i;
    light += frame0.records[i].contribution.x + frame0.records[i].radiance_before.x;
  }
  EXPECT_GT(light, 0.0);

  options.frame = 1;
  const RecordBatch frame1 = TraceRecords(animated, options).batch;
  for (const Record& r : frame1.records) {
    EXPECT_EQ(r.contribution, glm::vec4(0.0f));
    EXPECT_EQ(r.radiance_before, glm::vec4(0.0f));
  }
}

}  // namespace
}  // namespace hpsf
