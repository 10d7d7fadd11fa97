// Scene files (core/scene_file.h): hand-derived values of small files, the built-in scenes'
// files against make_builtin_scene (every field, exact floats) and against the golden images,
// the benchmark grid file against make_bench_scene, and the bad-file corpus of tests/data/bad/.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "core/model_import.h"
#include "core/scene_file.h"
#include "tests/golden.h"
#include "tests/support/bad_corpus.h"
#include "tests/support/scene_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

const std::string kScenes = TESSERA_SCENES_DIR;
const std::string kData = TESSERA_TEST_DATA_DIR;

SceneFile load(const std::string& text, SceneFileOptions options = {}) {
  return load_scene_text(text, "test.json", kData, options);
}

std::string load_error(const std::string& text, SceneFileOptions options = {}) {
  try {
    load(text, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SceneFile, BuiltinScenesFilesGiveTheSameScenes) {
  for (const BuiltinSceneInfo& info : builtin_scenes()) {
    SCOPED_TRACE(std::string(info.name));
    const SceneFile file = load_scene_file(kScenes + "/" + std::string(info.name) + ".json",
                                           SceneFileOptions{.strict = true});
    EXPECT_TRUE(file.warnings.empty());
    EXPECT_EQ(file.description, info.description);
    expect_same_scene(file.scene, make_builtin_scene(info.name));
  }
}

TEST(SceneFile, BenchGridFileGivesTheBenchmarkGrid) {
  const SceneFile file =
      load_scene_file(kScenes + "/bench-grid.json", SceneFileOptions{.strict = true});
  expect_same_scene(file.scene, make_bench_scene("grid", 1000, 32, 1.0f));
}

TEST(SceneFile, ValuesReadByHand) {
  const SceneFile f = load(R"({
    "camera": {"position": [0, 0, 10], "vertical_fov_degrees": 90, "near": 0.5},
    "materials": [{"name": "gold", "preset": "gold", "roughness": 0.25},
                  {"name": "glow", "base_color": [0.1, 0.2, 0.3], "emissive": [2, 0, 0],
                   "emissive_map": "squares", "double_sided": true}],
    "textures": [{"name": "squares", "type": "checker", "size": 4, "cells": 2,
                  "wrap": ["clamp_to_edge", "mirrored_repeat"]}],
    "meshes": [{"name": "box", "type": "cube"}],
    "objects": [{"mesh": "box", "material": "gold", "translation": [1, 2, 3],
                 "rotation": {"axis": [0, 0, 1], "degrees": 90}, "scale": 2},
                {"mesh": "box", "material": "glow", "scale": [-1, 1, 1]}],
    "lights": [{"type": "spot", "position": [0, 5, 0], "direction": [0, -2, 0],
                "inner_angle_degrees": 30, "outer_angle_degrees": 60, "intensity": 40}],
    "render": {"width": 640, "height": 480, "exposure_ev": -1, "tonemap": "reinhard",
               "brdf": "filament", "energy_compensation": true, "view": "normal"}
  })");
  EXPECT_FLOAT_EQ(f.scene.camera.vertical_fov, 1.5707963f);  // pi / 2
  EXPECT_EQ(f.scene.camera.near_plane, 0.5f);
  // Gold's F0 in Filament's table, sRGB (1.00, 0.85, 0.57), decoded by hand:
  // ((0.85 + 0.055) / 1.055)^2.4 = 0.69203, ((0.57 + 0.055) / 1.055)^2.4 = 0.28466; metallic.
  EXPECT_NEAR(f.scene.materials[0].base_color.r, 1.0f, 1e-6f);
  EXPECT_NEAR(f.scene.materials[0].base_color.g, 0.69203f, 1e-4f);
  EXPECT_NEAR(f.scene.materials[0].base_color.b, 0.28466f, 1e-4f);
  EXPECT_EQ(f.scene.materials[0].metallic, 1.0f);
  EXPECT_EQ(f.scene.materials[0].roughness, 0.25f);
  EXPECT_EQ(f.scene.materials[1].emissive, glm::vec3(2, 0, 0));
  EXPECT_EQ(f.scene.textures[0].wrap_u, TextureWrap::clamp_to_edge);
  EXPECT_EQ(f.scene.textures[0].wrap_v, TextureWrap::mirrored_repeat);
  EXPECT_EQ(f.scene.materials[1].roughness, 0.5f);  // the default
  EXPECT_EQ(f.scene.materials[1].emissive_map, 0u);
  EXPECT_TRUE(f.scene.materials[1].double_sided);
  EXPECT_FALSE(f.scene.materials[0].double_sided);
  EXPECT_TRUE(f.scene.textures[0].srgb);
  // T R S: (1, 0, 0) scaled to (2, 0, 0), turned to (0, 2, 0), moved to (1, 4, 3).
  const glm::vec4 p = f.scene.objects[0].transform * glm::vec4(1, 0, 0, 1);
  EXPECT_NEAR(p.x, 1.0f, 1e-6f);
  EXPECT_NEAR(p.y, 4.0f, 1e-6f);
  EXPECT_NEAR(p.z, 3.0f, 1e-6f);
  // A negative scale mirrors (allowed).
  EXPECT_LT(glm::determinant(f.scene.objects[1].transform), 0.0f);
  const Light& spot = f.scene.lights[0];
  EXPECT_EQ(spot.kind, LightKind::spot);
  EXPECT_EQ(spot.direction, glm::vec3(0, -1, 0));  // normalized
  EXPECT_FLOAT_EQ(spot.inner_angle, 0.52359878f);  // pi / 6
  EXPECT_FLOAT_EQ(spot.outer_angle, 1.0471976f);   // pi / 3
  EXPECT_EQ(*f.render.width, 640u);
  EXPECT_EQ(*f.render.height, 480u);
  EXPECT_EQ(*f.render.exposure_ev, -1.0f);
  EXPECT_EQ(*f.render.tonemap, ToneMap::reinhard);
  EXPECT_EQ(*f.render.brdf, Brdf::filament);
  EXPECT_EQ(f.render.energy_compensation, true);
  EXPECT_EQ(f.render.view, View::normal);
}

// A second uv set: "uvs1" on a triangles mesh, "MAP_uv_set": 1 on a material's map.
TEST(SceneFile, SecondUvSet) {
  const auto text = [](const char* set, const char* uvs1) {
    return std::string(R"({
    "textures": [{"name": "squares", "type": "checker", "size": 4, "cells": 2}],
    "materials": [{"name": "m", "base_color_map": "squares", "emissive_map": "squares",
                   "emissive_map_uv_set": )") +
           set + R"(}],
    "meshes": [{"name": "t", "type": "triangles", "positions": [0, 0, 0, 1, 0, 0, 0, 1, 0],
                "normals": [0, 0, 1, 0, 0, 1, 0, 0, 1], "uvs": [0, 0, 1, 0, 0, 1],
                "uvs1": )" +
           uvs1 + R"(, "indices": [0, 1, 2]}],
    "objects": [{"mesh": "t", "material": "m"}]
  })";
  };
  const char* uvs1 = "[0.5, 0.5, 0.25, 0.5, 0.5, 0.75]";
  const SceneFile f = load(text("1", uvs1));
  EXPECT_EQ(f.scene.materials[0].uv1_maps, TS_MAP_EMISSIVE);
  const std::vector<glm::vec2> expected = {{0.5f, 0.5f}, {0.25f, 0.5f}, {0.5f, 0.75f}};
  EXPECT_EQ(f.scene.meshes[0].uvs1, expected);
  EXPECT_EQ(load(text("0", uvs1)).scene.materials[0].uv1_maps, 0u);
  EXPECT_NE(load_error(text("2", uvs1)).find("materials.m.emissive_map_uv_set: 2 is outside"),
            std::string::npos)
      << load_error(text("2", uvs1));
  EXPECT_NE(load_error(text("1", "[0.5, 0.5, 0.25, 0.5]")).find("uvs1 gives 2 vertices"),
            std::string::npos)
      << load_error(text("1", "[0.5, 0.5, 0.25, 0.5]"));
  EXPECT_NE(load_error(R"({
    "textures": [{"name": "squares", "type": "checker", "size": 4, "cells": 2}],
    "materials": [{"name": "m", "base_color_map": "squares", "base_color_map_uv_set": 1}],
    "meshes": [{"name": "c", "type": "cube"}], "objects": [{"mesh": "c", "material": "m"}]})")
                .find("material 0 reads uv set 1, which mesh 0 does not have"),
            std::string::npos);
}

TEST(SceneFile, GridLayoutAndMaterialTiling) {
  const SceneFile f = load(R"({
    "materials": [{"name": "a"}, {"name": "b"}, {"name": "c"}, {"name": "d"}],
    "meshes": [{"name": "s", "type": "sphere", "segments": 8}],
    "objects": [{"mesh": "s", "materials": ["a", "b", "c", "d"], "tile_columns": 2,
                 "grid": {"count": [3, 2, 1], "spacing": [3, 2, 1], "limit": 5},
                 "translation": [0, 0, -10]}]
  })");
  ASSERT_EQ(f.scene.objects.size(), 5u);  // 6 cells, limited to 5
  // Centred: x in {-3, 0, 3}, y in {-1, 1}; then moved to z = -10.
  EXPECT_EQ(glm::vec3(f.scene.objects[0].transform[3]), glm::vec3(-3, -1, -10));
  EXPECT_EQ(glm::vec3(f.scene.objects[4].transform[3]), glm::vec3(0, 1, -10));
  // Materials as 2 columns x 2 rows: cell (x, y) takes (y % 2) * 2 + x % 2.
  const uint32_t want[] = {0, 1, 0, 2, 3};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(f.scene.objects[i].material, want[i]) << i;
}

TEST(SceneFile, RandomGeneratorIsMt19937WithAFixedMapping) {
  // std::mt19937's first output for seed 5489 is 3499211612 (the C++ standard fixes the
  // sequence); 3499211612 / 2^32 = 0.81472369...
  EXPECT_NEAR(uniform_float(3499211612u), 0.81472369f, 1e-7f);
  EXPECT_LT(uniform_float(0xFFFFFFFFu), 1.0f);
  EXPECT_EQ(uniform_float(0), 0.0f);
  const std::string text = R"({
    "materials": [{"name": "a"}],
    "meshes": [{"name": "s", "type": "cube"}],
    "objects": [{"mesh": "s", "material": "a",
                 "random": {"count": 100, "seed": 5489, "min": [0, 0, 0], "max": [1, 2, 4]}}]
  })";
  const SceneFile f = load(text);
  ASSERT_EQ(f.scene.objects.size(), 100u);
  EXPECT_NEAR(f.scene.objects[0].transform[3].x, 0.81472369f, 1e-7f);
  for (const Object& o : f.scene.objects) {
    const glm::vec3 p(o.transform[3]);
    EXPECT_TRUE(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 2 && p.z >= 0 && p.z < 4);
  }
  expect_same_scene(load(text).scene, f.scene);  // the same seed, the same scene
}

TEST(SceneFile, ModelFilesArePlacedAsAUnit) {
  const ImportedModel model = import_gltf(kData + "/features.gltf");
  const SceneFile f = load(R"({
    "models": [{"name": "features", "file": "features.gltf"}],
    "objects": [{"model": "features", "translation": [10, 0, 0]},
                {"model": "features", "translation": [-10, 0, 0]}]
  })");
  EXPECT_EQ(f.scene.meshes.size(), model.scene.meshes.size());  // shared by both placements
  EXPECT_EQ(f.scene.materials.size(), model.scene.materials.size());
  ASSERT_EQ(f.scene.objects.size(), 2 * model.scene.objects.size());
  for (size_t i = 0; i < model.scene.objects.size(); ++i) {
    const glm::vec4 origin = model.scene.objects[i].transform * glm::vec4(0, 0, 0, 1);
    const glm::vec4 moved = f.scene.objects[i].transform * glm::vec4(0, 0, 0, 1);
    EXPECT_NEAR(moved.x, origin.x + 10.0f, 1e-4f);
    EXPECT_EQ(moved.y, origin.y);
  }
  // The model's lights come once, where its first instance puts it.
  ASSERT_FALSE(model.scene.lights.empty());
  ASSERT_EQ(f.scene.lights.size(), model.scene.lights.size());
  for (size_t i = 0; i < model.scene.lights.size(); ++i) {
    EXPECT_EQ(f.scene.lights[i].position, model.scene.lights[i].position + glm::vec3(10, 0, 0));
    EXPECT_EQ(f.scene.lights[i].direction, model.scene.lights[i].direction);
  }
}

// A generator over a model places the whole model at each cell or draw (a fresh user's trial:
// the grid divided by the model's empty material list).
TEST(SceneFile, GeneratorsPlaceModels) {
  const ImportedModel model = import_gltf(kData + "/features.gltf");
  const SceneFile grid = load(R"({
    "models": [{"name": "features", "file": "features.gltf"}],
    "objects": [{"model": "features", "grid": {"count": [3, 2, 1], "spacing": 10}}]
  })");
  ASSERT_EQ(grid.scene.objects.size(), 6 * model.scene.objects.size());
  for (size_t cell = 0; cell < 6; ++cell) {
    for (size_t i = 0; i < model.scene.objects.size(); ++i) {
      const Object& o = grid.scene.objects[cell * model.scene.objects.size() + i];
      EXPECT_EQ(o.material, model.scene.objects[i].material);
      // Cell (ix, iy) of a 3 x 2 grid 10 apart, centred: x = (ix - 1) 10, y = (iy - 0.5) 10.
      const glm::vec4 origin = model.scene.objects[i].transform * glm::vec4(0, 0, 0, 1);
      const glm::vec4 moved = o.transform * glm::vec4(0, 0, 0, 1);
      EXPECT_NEAR(moved.x - origin.x, (float(cell % 3) - 1.0f) * 10.0f, 1e-4f);
      EXPECT_NEAR(moved.y - origin.y, (float(cell / 3) - 0.5f) * 10.0f, 1e-4f);
    }
  }
  const SceneFile random = load(R"({
    "models": [{"name": "features", "file": "features.gltf"}],
    "objects": [{"model": "features", "random": {"count": 4, "min": [0, 0, 0], "max": [1, 1, 1]}}]
  })");
  EXPECT_EQ(random.scene.objects.size(), 4 * model.scene.objects.size());
}

// Model files are told apart by their extension in either case: "BOX.GLB" from a Windows tool
// is a binary glTF (a fresh user's trial found it refused).
TEST(SceneFile, ModelExtensionsInUpperCase) {
  EXPECT_EQ(model_extension("dir.v2/BOX.GLB"), ".glb");
  EXPECT_EQ(model_extension("a/Spider.Obj"), ".obj");
  EXPECT_EQ(model_extension("dir.v2/noext"), "");
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "upper_case";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(
      "/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", dir / "BOX.GLB",
      std::filesystem::copy_options::overwrite_existing);
  const std::string scene = (dir / "scene.json").string();
  std::ofstream(scene) << R"({"models": [{"name": "box", "file": "BOX.GLB"}],
                             "objects": [{"model": "box"}]})";
  EXPECT_EQ(load_scene_file(scene).scene.objects.size(), 1u);
}

// A model's glTF cameras come with the scene file, placed as the model's first instance
// (Cameras.gltf: a perspective camera with yfov 0.7 at node translation (0.5, 0.5, 3), looking
// down its -z; an orthographic one, which the importer gives as a 45-degree perspective
// camera), for `--camera N`.
TEST(SceneFile, ModelCamerasArePlacedWithTheirModel) {
  const std::string cameras = "/usr/share/assimp/models/glTF2/cameras/Cameras.gltf";
  const SceneFile placed = load(R"({"models": [{"name": "cams", "file": ")" + cameras + R"("}],
    "objects": [{"model": "cams", "translation": [10, 0, 0]},
                {"model": "cams", "translation": [-5, 0, 0]}]})");
  ASSERT_EQ(placed.model_cameras.size(), 2u);
  EXPECT_EQ(placed.model_camera_names,
            (std::vector<std::string>{"model 'cams' camera 0", "model 'cams' camera 1"}));
  const Camera& c = placed.model_cameras[0];
  EXPECT_EQ(c.position, glm::vec3(10.5f, 0.5f, 3.0f));
  EXPECT_EQ(c.target, glm::vec3(10.5f, 0.5f, 2.0f));
  EXPECT_EQ(c.up, glm::vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(c.vertical_fov, 0.7f);
  EXPECT_FLOAT_EQ(placed.model_cameras[1].vertical_fov, glm::radians(45.0f));
  // A model no object places keeps the file's placement; the scene's own camera is unchanged.
  const SceneFile unplaced =
      load(R"({"models": [{"name": "cams", "file": ")" + cameras + R"("}]})");
  ASSERT_EQ(unplaced.model_cameras.size(), 2u);
  EXPECT_EQ(unplaced.model_cameras[0].position, glm::vec3(0.5f, 0.5f, 3.0f));
  EXPECT_EQ(unplaced.scene.camera, Camera{});
  // Its meshes are not drawn, which is said (an error when strict).
  const std::string warnings = [&] {
    std::string all;
    for (const std::string& w : unplaced.warnings) all += w + "\n";
    return all;
  }();
  EXPECT_NE(warnings.find("models.cams: no object places model 'cams', so its meshes are not "
                          "drawn"),
            std::string::npos)
      << warnings;
}

// The scene's limits on positions, light intensities and ranges (core/scene.h) apply once a
// scene file has placed a model: where a model breaks one, the message names the model file and
// the place in it (the glTF node, primitive and POSITION element, light or camera; the OBJ
// line) after the scene file's place, as the importers' own errors are named. Without the model
// places it named only the scene file's entry ("test.json:2:14: objects[0]: invalid scene:
// object 0 reaches outside ...").
TEST(SceneFile, ModelsBreakingSceneLimitsAreNamedInTheModelFile) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "model_limits";
  fs::create_directories(dir);
  std::ifstream in(kData + "/features.gltf");
  const nlohmann::json features = nlohmann::json::parse(in);
  // The scene placing model file `name` (written from `doc`) once, at `placement`.
  const auto error = [&](const std::string& name, const std::string& text,
                         const std::string& placement = "") {
    std::ofstream(dir / name) << text;
    const std::string scene = "{\"models\": [{\"name\": \"m\", \"file\": \"" + name +
                              "\"}],\n \"objects\": [{\"model\": \"m\"" + placement + "}]}";
    try {
      load_scene_text(scene, "test.json", dir.string(), {});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const auto gltf = [&](const std::string& pointer, double value) {
    nlohmann::json doc = features;
    doc[nlohmann::json::json_pointer(pointer)] = value;
    return doc.dump();
  };
  const std::string file = (dir / "f.gltf").string() + ": ";
  const std::string object = "test.json:2:14: objects[0]: ", model = "test.json:1:13: models.m: ";
  const std::string outside =
      "invalid scene: object 0 reaches outside +-1e+15 m per coordinate "
      "in world space (meshes[0].primitives[0].attributes.POSITION ";
  // nodes[0] (translation 2e15, 2, 3) is the parent of nodes[1] (scale 2, mesh 0, no NORMAL:
  // flat, its vertices the strip's corners, the first (0, 0, 0)).
  EXPECT_EQ(error("f.gltf", gltf("/nodes/0/translation/0", 2e15)),
            object + file + "nodes[1]: " + outside + "value (0, 0, 0) is placed at (2e+15, 2, 3))");
  // Within the limit once the scene file scales it down: the limit is the scene's.
  EXPECT_EQ(error("f.gltf", gltf("/nodes/0/translation/0", 2e15), ", \"scale\": 0.25"), "no error");
  // Light 1 (nodes[4]) has range 7, light 0 (nodes[3], colour (1, 0.5, 0.25)) intensity 683 cd.
  const std::string light = "extensions.KHR_lights_punctual.lights[";
  EXPECT_EQ(error("f.gltf", gltf("/extensions/KHR_lights_punctual/lights/1/range", 2e9)),
            model + file + light +
                "1].range: invalid scene: light 1 range is 2e+09 m; it must be 0 (no fade) or "
                "within [0.001, 1e+09] m");
  // 1e30 cd / 683 lm/W = 1.46413e27 W/sr; 1e27 cd is 1.46e24 W/sr, within 1e26.
  EXPECT_EQ(error("f.gltf", gltf("/extensions/KHR_lights_punctual/lights/0/intensity", 1e30)),
            model + file + light +
                "0].intensity: invalid scene: light 0 intensity times color is 1.46413e+27, above "
                "1e+26 W/sr (KHR_lights_punctual's candela or lux divided by 683 lm/W)");
  EXPECT_EQ(error("f.gltf", gltf("/extensions/KHR_lights_punctual/lights/0/intensity", 1e27)),
            "no error");
  EXPECT_EQ(error("f.gltf", gltf("/nodes/3/translation/1", 2e15)),
            model + file + "nodes[3] (" + light +
                "0]): invalid scene: light 0 position is outside +-1e+15 m per coordinate");
  // cameras[0] is placed by nodes[2].
  EXPECT_EQ(error("f.gltf", gltf("/nodes/2/translation/2", 2e15)),
            model + "camera 0: " + file +
                "nodes[2] (cameras[0]): invalid scene: the camera's position is outside +-1e+15 m "
                "per coordinate");

  // A triangle with normals, whose vertices are POSITION's elements: element 1 is (2e15, 0, 0).
  const float data[18] = {0, 0, 0, 2e15f, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  std::ofstream(dir / "tri.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(data), sizeof data);
  const std::string tri = R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
       "min": [0, 0, 0], "max": [2e15, 1, 0]},
      {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "bufferViews": [{"buffer": 0, "byteLength": 72}],
    "buffers": [{"uri": "tri.bin", "byteLength": 72}]})";
  EXPECT_EQ(error("tri.gltf", tri, ", \"translation\": [0, 0, 5]"),
            object + (dir / "tri.gltf").string() + ": nodes[0]: " + outside +
                "element 1, (2e+15, 0, 0), is placed at (2e+15, 0, 5))");
  // OBJ places its errors by line: the vertex's.
  EXPECT_EQ(error("tri.obj", "# a triangle\nv 0 0 0\nv 2e15 0 0\nv 0 1 0\nf 1 2 3\n"),
            object + "'" + (dir / "tri.obj").string() +
                "' line 3: invalid scene: object 0 reaches outside +-1e+15 m per coordinate in "
                "world space (its vertex (2e+15, 0, 0) is placed at (2e+15, 0, 0))");
}

// The example scene files of examples/scenes/ (the ones docs/gltf.md renders) load without an
// unknown key and place something: they are kept working. Their models' own warnings (the
// BoxTextured sampler's wrap modes) are allowed.
TEST(SceneFile, ExampleScenesLoad) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(TESSERA_EXAMPLE_SCENES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    ++files;
    const SceneFile f = load_scene_file(entry.path().string());
    EXPECT_FALSE(f.scene.objects.empty());
    EXPECT_FALSE(f.description.empty());
    for (const std::string& w : f.warnings) {
      EXPECT_EQ(w.find("unknown key"), std::string::npos) << w;
    }
  }
  EXPECT_GE(files, 4);
}

// A number beyond double's range is named by its path, as other errors name their values
// (tests/data/bad/scene_inf*.json), where the rest of the file parses; with a second such
// number after it, by its place alone.
TEST(SceneFile, NumberOutOfRangeIsNamedByItsPath) {
  EXPECT_EQ(load_error("1e999"),
            "test.json:1:1: (top level): 1e999 is out of the range of a number (NaN and infinity "
            "are refused)");
  EXPECT_EQ(load_error(R"({"a/b~": 1e999})"),
            "test.json:1:10: a/b~: 1e999 is out of the range of a number (NaN and infinity are "
            "refused)");
  EXPECT_EQ(load_error(R"({"x": [1e999, 2e999]})"),
            "test.json:1:8: 1e999 is out of the range of a number (NaN and infinity are refused)");
}

TEST(SceneFile, UnknownKeysWarnAndFailWhenStrict) {
  const std::string text = R"({
  "camera": {"position": [0, 0, 5]},
  "colour": [1, 0, 0]
})";
  const SceneFile f = load(text);
  ASSERT_EQ(f.warnings.size(), 1u);
  EXPECT_EQ(f.warnings[0], "test.json:3:3: colour: unknown key 'colour' (ignored)");
  EXPECT_NE(load_error(text, {.strict = true}).find("test.json:3:3: colour: unknown key"),
            std::string::npos);
}

// A misspelt key gets the nearest known one, where one is a slip away ("light" for "lights",
// one edit; "metalic" for "metallic", one); a key near none gets no guess.
TEST(SceneFile, UnknownKeysSuggestTheNearestKnownOne) {
  const SceneFile f = load(R"({"light": [],
 "materials": [{"name": "m", "metalic": 1, "shine": 2}]})");
  ASSERT_EQ(f.warnings.size(), 3u);
  EXPECT_EQ(f.warnings[0],
            "test.json:1:2: light: unknown key 'light', did you mean 'lights'? (ignored)");
  EXPECT_NE(f.warnings[1].find("materials.m.metalic: unknown key 'metalic', did you mean "
                               "'metallic'? (ignored)"),
            std::string::npos)
      << f.warnings[1];
  EXPECT_NE(f.warnings[2].find("materials.m.shine: unknown key 'shine' (ignored)"),
            std::string::npos)
      << f.warnings[2];
  EXPECT_NE(load_error(R"({"light": []})", {.strict = true})
                .find("unknown key 'light', did you mean 'lights'? (an error with --strict)"),
            std::string::npos);
}

// A format version other than 1 is named as such (it read "2 is outside [1, 1]").
TEST(SceneFile, OtherFormatVersionsAreRefusedByName) {
  EXPECT_EQ(load_error(R"({"version": 2})"),
            "test.json:1:13: version: format version 2 is not one this Tessera reads (version 1 "
            "only)");
  EXPECT_EQ(load_error(R"({"version": 1.5})"),
            "test.json:1:13: version: format version 1.5 is not one this Tessera reads (version "
            "1 only)");
  EXPECT_NE(load_error(R"({"version": "1"})").find("version: must be an integer"),
            std::string::npos);
  EXPECT_EQ(load_error(R"({"version": 1})"), "");
}

// A misspelt key whose absence makes the file fail ("materal": the object's material is then
// unknown) keeps its "did you mean" in the error, which would otherwise drop the warning (a
// fresh user's trial saw only the error).
TEST(SceneFile, AnErrorKeepsTheUnknownKeysReadBeforeIt) {
  const std::string message = load_error(R"({
  "meshes": [{"name": "ball", "type": "sphere"}],
  "materal": [{"name": "m"}],
  "objects": [{"mesh": "ball", "material": "m"}]
})");
  EXPECT_NE(message.find("objects[0].material"), std::string::npos) << message;
  EXPECT_NE(message.find("\n  test.json:3:3: materal: unknown key 'materal', did you mean "
                         "'materials'? (ignored)"),
            std::string::npos)
      << message;
  // An error with no unknown key before it is unchanged.
  EXPECT_EQ(load_error(R"({"objects": [{"mesh": "ball"}]})").find('\n'), std::string::npos);
}

// The BRDF is spelt blinn_phong in scene files and blinn-phong on the command line; each place
// takes both (a new user's trial wrote the command line's).
TEST(SceneFile, ChoicesTakeHyphenOrUnderscore) {
  for (const char* name : {"blinn_phong", "blinn-phong"}) {
    const SceneFile f = load(std::string(R"({"render": {"brdf": ")") + name + R"("}})");
    ASSERT_TRUE(f.render.brdf) << name;
    EXPECT_EQ(*f.render.brdf, Brdf::blinn_phong) << name;
  }
  EXPECT_NE(load_error(R"({"render": {"brdf": "phong"}})")
                .find("'phong' is not one of classic, filament, blinn_phong"),
            std::string::npos);
}

TEST(SceneFile, LimitsAreOptions) {
  const std::string grid =
      R"({"materials": [{"name": "a"}], "meshes": [{"name": "s", "type": "cube"}],
    "objects": [{"mesh": "s", "material": "a", "grid": {"count": [10, 10, 1]}}]})";
  EXPECT_EQ(load(grid).scene.objects.size(), 100u);
  EXPECT_NE(load_error(grid, {.max_objects = 99}).find("makes 100 objects, over the limit of 99"),
            std::string::npos);
  EXPECT_NE(load_error(grid, {.max_file_bytes = 20}).find("over the limit of 20 bytes"),
            std::string::npos);
  EXPECT_NE(load_error(R"({"meshes": [{"name": "s", "type": "sphere", "segments": 1000,
    "rings": 1000}]})",
                       {.max_mesh_vertices = 1000})
                .find("1002001 vertices, over the limit"),
            std::string::npos);
}

// Each tests/data/bad/scene_NAME.json must fail (strict, files over 16 KiB refused) with the
// text of scene_NAME.expected.
TEST(SceneFile, BadFilesGiveTheirExpectedErrors) {
  const auto error_of = [](const std::string& path) -> std::string {
    try {
      load_scene_file(path, {.strict = true, .max_file_bytes = 16384});
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_GE(testing::expect_bad_corpus(kData + "/bad", "scene_", ".json", error_of), 20);
}

// `tessera render --scene FILE` takes the file's render defaults unless the command line sets
// them; a bad file exits with status 1 and the place; `tessera scenes` lists the files.
TEST(SceneFileCli, RenderUsesTheFileAndItsDefaults) {
  const std::string scene = test::output_path("small.json");
  std::ofstream(scene)
      << R"({"materials": [{"name": "m"}], "meshes": [{"name": "c", "type": "cube"}],
    "objects": [{"mesh": "c", "material": "m"}], "render": {"width": 40, "height": 30}})";
  const std::string png = test::output_path("small.png");
  std::string out;
  ASSERT_EQ(
      test::run_command(
          std::string(TESSERA_BINARY) + " render --quiet --scene " + scene + " --out " + png, out),
      0)
      << out;
  EXPECT_EQ(read_png(png).width, 40u);
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " render --quiet --size 20x10 --scene " + scene + " --out " + png,
                              out),
            0)
      << out;
  EXPECT_EQ(read_png(png).width, 20u);
  EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) + " render --scene " + kData +
                                  "/bad/scene_range.json --out " + png,
                              out),
            1);
  EXPECT_NE(out.find("scene_range.json:4:19: materials.gold.roughness: 1.5 is outside [0, 1]"),
            std::string::npos)
      << out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) + " scenes", out), 0);
  for (const BuiltinSceneInfo& info : builtin_scenes())
    EXPECT_NE(out.find(std::string(info.name) + " "), std::string::npos) << out;
}

// `--camera N` views a scene file through its models' camera N; past the last one, or for a
// scene whose models bring none, it says which cameras there are, as a bad command line (exit
// status 2 and where the usage is, though found only once the scene is loaded).
TEST(SceneFileCli, CameraPicksAModelCamera) {
  const std::string scene = test::output_path("cameras.json");
  std::ofstream(scene) << R"({"models": [{"name": "cams", "file":
    "/usr/share/assimp/models/glTF2/cameras/Cameras.gltf"}], "objects": [{"model": "cams"}],
    "ambient": [1, 1, 1]})";
  const std::string own = test::output_path("camera_own.png"),
                    picked = test::output_path("camera_0.png");
  const std::string render = std::string(TESSERA_BINARY) + " render --quiet --size 48x48 --scene ";
  std::string out;
  ASSERT_EQ(test::run_command(render + scene + " --out " + own, out), 0) << out;
  ASSERT_EQ(test::run_command(render + scene + " --camera 0 --out " + picked, out), 0) << out;
  EXPECT_NE(read_png(own).pixels, read_png(picked).pixels);
  EXPECT_EQ(test::run_command(render + scene + " --camera 2 --out " + picked, out), 2);
  EXPECT_NE(out.find("tessera: error: --camera 2: the scene's models bring 2 cameras (0: model "
                     "'cams' camera 0, 1: model 'cams' camera 1)\nRun 'tessera render --help' "
                     "for the options."),
            std::string::npos)
      << out;
  EXPECT_EQ(test::run_command(render + "spheres --camera 0 --out " + picked, out), 2);
  EXPECT_NE(out.find("--camera 0: the scene's models bring no cameras"), std::string::npos) << out;
  EXPECT_NE(out.find("Run 'tessera render --help' for the options."), std::string::npos) << out;
}

// A scene with nothing to light it is valid: its objects are black. `render` says so in a
// note, which --strict does not make an error, and says nothing where anything gives light or
// a debug view needs none.
TEST(SceneFileCli, UnlitSceneIsNoted) {
  const std::string cube = R"("meshes": [{"name": "c", "type": "cube"}],
    "objects": [{"mesh": "c", "material": "m"}])";
  const std::string unlit = test::output_path("unlit.json");
  std::ofstream(unlit) << R"({"materials": [{"name": "m"}, {"name": "glow", "emissive": [1, 1, 1]}],
    )" + cube + "}";
  const std::string glowing = test::output_path("glowing.json");
  std::ofstream(glowing) << R"({"materials": [{"name": "m", "emissive": [1, 1, 1]}], )" + cube +
                                "}";
  const std::string ambient = test::output_path("ambient.json");
  std::ofstream(ambient) << R"({"materials": [{"name": "m"}], "ambient": [0.1, 0, 0], )" + cube +
                                "}";
  const std::string render = std::string(TESSERA_BINARY) +
                             " render --device lavapipe --size 16x16 --repeat 1 --out " +
                             test::output_path("unlit.png") + " --scene ";
  const std::string note = "tessera: note: " + unlit +
                           " has no lights, ambient light, environment or emissive material: its "
                           "objects are black\n";
  std::string out;
  EXPECT_EQ(test::run_command(render + unlit + " --strict", out), 0) << out;
  EXPECT_NE(out.find(note), std::string::npos) << out;
  EXPECT_EQ(out.find("warning"), std::string::npos) << out;
  // The emissive material above is on no object; here it is. Lights, an environment: below.
  for (const std::string& lit : {glowing + " ", ambient + " ", unlit + " --env sky",
                                 unlit + " --view normal", std::string("spheres")}) {
    EXPECT_EQ(test::run_command(render + lit, out), 0) << out;
    EXPECT_EQ(out.find("note:"), std::string::npos) << lit << ":\n" << out;
  }
  // A file lit by its environment alone is black once --env none removes it: the note says
  // that, not that the file has no environment. Without an environment to remove, --env none
  // leaves the note as it was.
  const std::string sky = test::output_path("sky_only.json");
  std::ofstream(sky) << R"({"materials": [{"name": "m"}], "environment": "sky", )" + cube + "}";
  EXPECT_EQ(test::run_command(render + sky + " --env none", out), 0) << out;
  EXPECT_NE(out.find("tessera: note: --env none removed the environment that lit " + sky +
                     ", which has no lights, ambient light or emissive material: its objects "
                     "are black\n"),
            std::string::npos)
      << out;
  EXPECT_EQ(test::run_command(render + sky, out), 0) << out;
  EXPECT_EQ(out.find("note:"), std::string::npos) << out;
  EXPECT_EQ(test::run_command(render + unlit + " --env none", out), 0) << out;
  EXPECT_NE(out.find(note), std::string::npos) << out;
}

// A scene file whose objects need a larger object buffer than the device binds (lavapipe: 128
// MiB, 160 bytes an object, so under 840,000 objects) is refused naming the file.
TEST(SceneFileCli, SceneTooLargeForTheDeviceNamesTheFile) {
  const std::string path = test::output_path("too_many.json");
  std::ofstream(path) << R"({"materials": [{"name": "m"}], "ambient": [1, 1, 1],
    "meshes": [{"name": "c", "type": "cube"}],
    "objects": [{"mesh": "c", "material": "m", "grid": {"count": [1000, 1000, 1]}}]})";
  std::string out;
  EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " render --device lavapipe --size 16x16 --out " +
                                  test::output_path("too_many.png") + " --scene " + path,
                              out),
            1)
      << out;
  EXPECT_NE(out.find("tessera: error: " + path + ": the scene needs a "), std::string::npos) << out;
  EXPECT_NE(out.find(" object buffer (1000000 objects), more than this device's "
                     "maxStorageBufferRange (128 MiB)"),
            std::string::npos)
      << out;
}

// An object far from the origin for its size is noted with the spacing of 32-bit floats there:
// a cube of side 2 at x = 10^6 reaches 1000001, between 2^19 and 2^20, where floats are 2^-4 =
// 0.0625 apart, 1/32 of its side. The same cube at x = 1000 is not noted (2^-14 apart), nor the
// far one on the reference, which computes in double.
TEST(SceneFileCli, ObjectsFarFromTheOriginAreNoted) {
  const auto write = [](const std::string& name, const char* x) {
    const std::string path = test::output_path(name);
    std::ofstream(path) << R"({"materials": [{"name": "m"}], "ambient": [1, 1, 1],
      "meshes": [{"name": "c", "type": "cube"}], "camera": {"position": [)"
                        << x << R"(, 0, 8], "target": [)" << x << R"(, 0, 0]},
      "objects": [{"mesh": "c", "material": "m", "translation": [)"
                        << x << R"(, 0, 0]},
        {"mesh": "c", "material": "m", "translation": [)"
                        << x << ", 3, 0]}]}";
    return path;
  };
  const std::string far = write("far.json", "1000000"), near = write("near.json", "1000");
  const std::string render = std::string(TESSERA_BINARY) +
                             " render --size 16x16 --repeat 1 --out " +
                             test::output_path("far.png") + " --scene ";
  std::string out;
  EXPECT_EQ(test::run_command(render + far + " --device lavapipe", out), 0) << out;
  EXPECT_NE(out.find("tessera: note: object 0 of " + far +
                     " lies 1e+06 m from the origin, where 32-bit positions are 0.0625 m apart, "
                     "1/32 of its size, as 1 more objects are: "),
            std::string::npos)
      << out;
  EXPECT_EQ(test::run_command(render + near + " --device lavapipe", out), 0) << out;
  EXPECT_EQ(out.find("note:"), std::string::npos) << out;
  EXPECT_EQ(test::run_command(render + far + " --device reference", out), 0) << out;
  EXPECT_EQ(out.find("note:"), std::string::npos) << out;
}

// A light nearer than 1 cm to an object meets the shading's distance floor, which leaves a
// micrometre scene nearly black: `render` notes the first such light with its nearest object and
// distance (a cube of side 2 um at the origin, lights 3 um above and 4 um before its centre: 2
// and 3 um from its box) and how many more there are, on the GPU and the reference alike
// (both floor the distance), and not under --quiet. The same scene a million times larger, its
// intensities 10^12 times, is lit as 1/d^2 says and not noted.
TEST(SceneFileCli, LightsWithinTheDistanceFloorAreNoted) {
  // U: the unit's exponent, I: the intensity.
  const auto write = [](const std::string& name, const std::string& unit,
                        const std::string& intensity) {
    std::string text = R"({"materials": [{"name": "m"}], "meshes": [{"name": "c", "type": "cube"}],
      "camera": {"position": [0, 0, 8U], "near": 1U},
      "objects": [{"mesh": "c", "material": "m", "scale": 1U}],
      "lights": [{"type": "point", "position": [0, 3U, 0], "intensity": I},
        {"type": "spot", "position": [0, 0, 4U], "direction": [0, 0, -1], "intensity": I}]})";
    for (size_t at; (at = text.find_first_of("UI")) != std::string::npos;)
      text.replace(at, 1, text[at] == 'U' ? unit : intensity);
    const std::string path = test::output_path(name);
    std::ofstream(path) << text;
    return path;
  };
  const std::string micro = write("micro.json", "e-6", "1e-12"),
                    metre = write("metre.json", "e0", "1");
  const std::string render = std::string(TESSERA_BINARY) +
                             " render --size 16x16 --repeat 1 --out " +
                             test::output_path("micro.png") + " --scene ";
  const std::string note =
      "tessera: note: light 0 of " + micro +
      " lies 2e-06 m from object 0, as 1 more light lies within 1 cm of an "
      "object: the shading treats distances below 1 cm as 1 cm, so surfaces nearer receive less "
      "than intensity / d^2, and a scene modelled below centimetre scale renders too dark unless "
      "scaled up (lengths by k, intensities by k^2; docs/shading.md)\n";
  std::string out;
  for (const char* device : {" --device lavapipe", " --device reference"}) {
    EXPECT_EQ(test::run_command(render + micro + device, out), 0) << out;
    EXPECT_NE(out.find(note), std::string::npos) << device << ":\n" << out;
  }
  EXPECT_EQ(test::run_command(render + micro + " --device lavapipe --quiet", out), 0) << out;
  EXPECT_EQ(out.find("note:"), std::string::npos) << out;
  EXPECT_EQ(test::run_command(render + metre + " --device lavapipe", out), 0) << out;
  EXPECT_EQ(out.find("note:"), std::string::npos) << out;
}

// Every scene `tessera scenes` lists renders by its name, and a model file renders as a scene
// (tests/model_scene_test.cpp), also named without a folder from the folder it is in (a fresh
// user's trial was told "unknown scene" for that).
TEST(SceneFileCli, ListedScenesAndModelFilesRenderByName) {
  const std::string png = test::output_path("named.png");
  std::string out;
  EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " render --quiet --size 32x32 --scene bench-grid --out " + png,
                              out),
            0)
      << out;
  EXPECT_EQ(read_png(png).width, 32u);
  // The output path made absolute: the command runs in the model's folder.
  EXPECT_EQ(test::run_command("cd " + kData + " && " + TESSERA_BINARY +
                                  " render --quiet --size 16x16 --scene features.gltf --out " +
                                  std::filesystem::absolute(png).string(),
                              out),
            0)
      << out;
  EXPECT_EQ(read_png(png).width, 16u);
}

// `tessera scenes` lists a file that cannot load with its error, not with a blank description;
// a TESSERA_SCENES that names no folder is said once, not passed over in silence (both from a
// new user's trial).
TEST(SceneFileCli, ScenesListsBrokenFilesAndAMissingFolder) {
  const std::filesystem::path dir = test::output_path("listed_scenes");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "empty.json").flush();
  std::ofstream(dir / "plain.json") << R"({"description": "a plain scene"})";
  std::ofstream(dir / "metals.json") << R"({"description": "my metals"})";
  std::string out;
  EXPECT_EQ(
      test::run_command("TESSERA_SCENES=" + dir.string() + " " + TESSERA_BINARY + " scenes", out),
      0);
  EXPECT_NE(out.find("scene files in " + dir.string()), std::string::npos) << out;
  // The built-in scenes, which still load by name, are listed after it (they were hidden), and
  // the one its metals.json comes before is marked.
  const size_t builtin = out.find("scene files in ", out.find("scene files in ") + 1);
  ASSERT_NE(builtin, std::string::npos) << out;
  EXPECT_NE(out.find("\nspheres      ", builtin), std::string::npos) << out;
  EXPECT_NE(out.find("metals       (not loaded by name: " + dir.string() + " has 'metals' first)",
                     builtin),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("metals       my metals\n"), std::string::npos) << out;
  EXPECT_NE(out.find("empty        (cannot be loaded: empty.json:1:1: JSON syntax error"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("plain        a plain scene\n"), std::string::npos) << out;
  const std::string missing = (dir / "nowhere").string();
  EXPECT_EQ(test::run_command("TESSERA_SCENES=" + missing + " " + TESSERA_BINARY +
                                  " render --scene nosuch --out x.png",
                              out),
            2);
  const std::string warning = "tessera: warning: TESSERA_SCENES is '" + missing +
                              "', which does not exist; scenes are looked for in the other "
                              "scene folders";
  const size_t at = out.find(warning);
  EXPECT_NE(at, std::string::npos) << out;
  EXPECT_EQ(out.find(warning, at + 1), std::string::npos) << "said twice: " << out;
  EXPECT_EQ(
      test::run_command(
          std::string("TESSERA_SCENES=") + TESSERA_BINARY + " " + TESSERA_BINARY + " scenes", out),
      0);
  EXPECT_NE(out.find("which is not a folder"), std::string::npos) << out;
}

// A scene without objects renders its background; the note says so, and not that "its objects
// are black" (a new user's trial), whether or not it has lights.
TEST(SceneFileCli, SceneWithoutObjectsIsNoted) {
  const std::string png = test::output_path("no_objects.png");
  for (const char* text : {"{}", R"({"lights": [{"type": "point", "position": [0, 1, 0]}]})"}) {
    const std::string file = test::output_path("no_objects.json");
    std::ofstream(file) << text;
    std::string out;
    EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                    " render --device lavapipe --size 16x16 --strict --scene " +
                                    file + " --out " + png,
                                out),
              0)
        << out;
    EXPECT_NE(out.find("tessera: note: " + file +
                       " has no objects: the image shows only the background\n"),
              std::string::npos)
        << text << ": " << out;
    EXPECT_EQ(out.find("black"), std::string::npos) << out;
  }
}

// A scene whose every triangle is culled renders its background with status 0; a note says
// why, by the counts (a new user's trial: OBJ models seen edge-on or from behind came out
// black with no word). One triangle wound clockwise as seen from the default camera, on +z.
TEST(SceneFileCli, SceneWithNothingDrawnIsNoted) {
  const std::string file = test::output_path("behind.json");
  std::ofstream(file) << R"({"meshes": [{"name": "t", "type": "triangles",
      "positions": [0, 0, 0, 0, 1, 0, 1, 0, 0], "normals": [0, 0, 1, 0, 0, 1, 0, 0, 1],
      "uvs": [0, 0, 0, 0, 0, 0], "indices": [0, 1, 2]}], "materials": [{"name": "m"}],
      "objects": [{"mesh": "t", "material": "m"}],
      "lights": [{"type": "directional", "direction": [0, 0, -1]}]})";
  std::string out;
  EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " render --device lavapipe --size 16x16 --strict --scene " +
                                  file + " --out " + test::output_path("behind.png"),
                              out),
            0)
      << out;
  EXPECT_NE(out.find("tessera: note: no triangle of " + file +
                     " was drawn, of 1 submitted: 1 back-facing (a material's double_sided "
                     "draws them); the image shows only the background\n"),
            std::string::npos)
      << out;
}

class SceneFileRender : public test::VulkanTest {};

// The built-in scenes' files render to the golden images, bit for bit.
TEST_F(SceneFileRender, BuiltinFilesMatchTheGoldenImages) {
  for (const BuiltinSceneInfo& info : builtin_scenes()) {
    SCOPED_TRACE(std::string(info.name));
    Renderer renderer(context(), RendererOptions{});
    renderer.set_scene(load_scene_file(kScenes + "/" + std::string(info.name) + ".json").scene);
    FrameSettings settings;
    settings.width = 96;  // as tests/golden_test.cpp
    settings.height = 72;
    renderer.render(settings);
    test::expect_golden(renderer, std::string(info.name));
  }
}

}  // namespace
}  // namespace tessera
