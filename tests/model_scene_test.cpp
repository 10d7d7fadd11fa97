// A model file given as a command's scene (`tessera render --scene model.obj`): placed once,
// seen through a camera that frames it, lit by a default sun where it brings no lights; a scene
// file placing the same model keeps its own camera and lights.
#include <algorithm>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/check.h"
#include "core/image.h"
#include "core/scene_file.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

const std::string kTool = TESSERA_BINARY;
const std::string kData = TESSERA_TEST_DATA_DIR;
const std::string kGltf = "/usr/share/assimp/models/glTF2/";

// A box from (100, -10, -10) to (140, 10, 10), its faces wound outward: far off the default
// camera's view (from (0, 0, 5) down -z), so a render of it unframed shows none of it.
std::string write_far_box() {
  const std::string path = test::output_path("far box.OBJ");  // a space and an upper-case suffix
  std::ofstream(path) << "v 100 -10 -10\nv 140 -10 -10\nv 140 10 -10\nv 100 10 -10\n"
                         "v 100 -10 10\nv 140 -10 10\nv 140 10 10\nv 100 10 10\n"
                         "f 5 6 7 8\nf 2 1 4 3\nf 6 2 3 7\nf 1 5 8 4\nf 8 7 3 4\nf 1 2 6 5\n";
  return path;
}

struct Box {
  uint32_t x0 = UINT32_MAX, y0 = UINT32_MAX, x1 = 0, y1 = 0;  // inclusive; x0 > x1 when empty
  uint32_t pixels = 0;
};

// The pixels that differ from the top left corner's (the background, where nothing is drawn).
Box drawn(const Image8& image) {
  const auto background = image.at(0, 0);
  Box b;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const auto p = image.at(x, y);
      if (p.r == background.r && p.g == background.g && p.b == background.b) continue;
      b.x0 = std::min(b.x0, x), b.y0 = std::min(b.y0, y);
      b.x1 = std::max(b.x1, x), b.y1 = std::max(b.y1, y);
      ++b.pixels;
    }
  }
  return b;
}

std::string quoted(const std::string& path) {
  return "'" + path + "'";
}

// The box's bounding sphere has centre (120, 0, 0) and radius sqrt(20^2 + 10^2 + 10^2) =
// 24.4949; framed in a square image at 45 degrees the eye is at 24.4949 / sin(22.5 deg) =
// 64.0087 on +z from the centre. Only the front face (z = 10, depth 54.0087) faces the eye; it
// reaches 20 / (54.0087 tan(22.5 deg)) = 0.89399 of the half width and 0.44700 of the half
// height: in 64 pixels, from 3.39 to 60.61 across and 17.70 to 46.30 down, which holds the
// centres (x + 0.5) of columns 3 to 60 and rows 18 to 45. The sun lights it at cos = 0.6 /
// |(-0.5, -0.8, -0.6)| = 0.5367.
TEST(ModelScene, RenderFramesAnObjModelAndLightsIt) {
  const std::string obj = write_far_box(), png = test::output_path("far_box.png");
  std::string out;
  ASSERT_EQ(test::run_command(kTool + " render --device lavapipe --size 64x64 --scene " +
                                  quoted(obj) + " --out " + png,
                              out),
            0)
      << out;
  EXPECT_NE(out.find("tessera: note: " + obj +
                     " has no lights: lit by the sun of the built-in scene 'textured'"),
            std::string::npos)
      << out;
  const Image8 image = read_png(png);
  const Box b = drawn(image);
  EXPECT_EQ(b.x0, 3u);
  EXPECT_EQ(b.x1, 60u);
  EXPECT_EQ(b.y0, 18u);
  EXPECT_EQ(b.y1, 45u);
  // Lit, not black: the face's middle is well above the background.
  const auto middle = image.at(32, 32);
  EXPECT_GT(int(middle.r) + middle.g + middle.b, 3 * 60) << "the framed face is lit";
}

// The same model placed by a scene file keeps that file's camera (the default one, which sees
// nothing of it) and lights (none: the file's usual note, not the model's).
TEST(ModelScene, AScenePlacingTheModelIsUnaffected) {
  const std::string obj = write_far_box(), png = test::output_path("far_box_scene.png");
  const std::string scene = test::output_path("far_box_scene.json");
  std::ofstream(scene) << R"({"models": [{"name": "box", "file": "far box.OBJ"}],
                              "objects": [{"model": "box"}]})";
  std::string out;
  ASSERT_EQ(
      test::run_command(
          kTool + " render --device lavapipe --size 64x64 --scene " + scene + " --out " + png, out),
      0)
      << out;
  EXPECT_EQ(out.find("lit by the sun"), std::string::npos) << out;
  EXPECT_NE(out.find("has no lights, ambient light, environment or emissive material"),
            std::string::npos)
      << out;
  EXPECT_EQ(drawn(read_png(png)).pixels, 0u) << "the default camera sees nothing of the box";
}

// A real glTF file: BoxTextured, a cube of side 1 about the origin. Its front face fills the
// middle 68% of a square image (the unit cube of tests/orbit_camera_test.cpp): the corners are
// background, the middle is the textured face.
TEST(ModelScene, RenderFramesAGlbModel) {
  const std::string png = test::output_path("box_textured.png");
  std::string out;
  ASSERT_EQ(test::run_command(kTool + " render --device lavapipe --size 64x64 --scene " + kGltf +
                                  "BoxTextured-glTF-Binary/BoxTextured.glb --out " + png,
                              out),
            0)
      << out;
  EXPECT_NE(out.find("BoxTextured.glb has no lights: lit by"), std::string::npos) << out;
  const Box b = drawn(read_png(png));
  // 0.6847 of the half width: columns 10.09 to 53.91.
  EXPECT_NEAR(int(b.x0), 10, 1);
  EXPECT_NEAR(int(b.x1), 53, 1);
  EXPECT_NEAR(int(b.y0), 10, 1);
  EXPECT_NEAR(int(b.y1), 53, 1);
}

// A model with lights of its own (KHR_lights_punctual) is lit by them alone: no note, no sun.
TEST(ModelScene, AModelWithLightsKeepsThem) {
  const SceneFile file = load_model_scene(kData + "/lamp.gltf");
  ASSERT_EQ(file.scene.lights.size(), 1u);
  EXPECT_EQ(file.scene.lights[0].kind, LightKind::point);
  std::string out;
  ASSERT_EQ(test::run_command(kTool + " render --device lavapipe --size 16x16 --scene " + kData +
                                  "/lamp.gltf --out " + test::output_path("lamp.png"),
                              out),
            0)
      << out;
  EXPECT_EQ(out.find("has no lights"), std::string::npos) << out;
}

// The file's cameras are there for --camera, numbered as a scene file's models number them.
TEST(ModelScene, CameraPicksTheModelsOwnCamera) {
  const std::string cameras = kGltf + "cameras/Cameras.gltf";
  const SceneFile file = load_model_scene(cameras);
  ASSERT_EQ(file.model_cameras.size(), 2u);
  EXPECT_EQ(file.model_camera_names[0], "model 'Cameras.gltf' camera 0");
  std::string out;
  EXPECT_EQ(test::run_command(kTool + " render --device lavapipe --size 16x16 --camera 2 " +
                                  "--scene " + cameras + " --out " + test::output_path("c.png"),
                              out),
            2)
      << out;
  EXPECT_NE(out.find("--camera 2: the scene's models bring 2 cameras (0: model 'Cameras.gltf' "
                     "camera 0, 1: model 'Cameras.gltf' camera 1)"),
            std::string::npos)
      << out;
}

// A broken model's message names the model file and its place, not the scene text made of it.
TEST(ModelScene, ErrorsNameTheModelFile) {
  const std::string obj = test::output_path("far_away.obj");
  std::ofstream(obj) << "v 0 0 0\nv 2e15 0 0\nv 0 1 0\nf 1 2 3\n";
  try {
    load_model_scene(obj);
    FAIL() << "loaded";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("'" + obj + "' line 2: invalid scene: object 0", 0), 0u) << message;
    EXPECT_EQ(message.find("models[0]"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace tessera
