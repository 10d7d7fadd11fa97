// Saving scenes (core/scene_file_write.h): every shipped scene file, every built-in scene, an
// imported glTF model, an edited scene and hand-made meshes, lights and environments round
// trip through save_scene_file and load_scene_file field by field; bad paths are named.
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/mesh.h"
#include "core/model_import.h"
#include "core/scene_edit.h"
#include "core/scene_file.h"
#include "core/scene_file_write.h"
#include "tests/support/scene_assertions.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
const std::string kScenes = TESSERA_SCENES_DIR;
const std::string kData = TESSERA_TEST_DATA_DIR;

// A fresh folder for this test's files.
std::string scratch_folder() {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  const fs::path p = fs::path("test_output") / "scene_file_write" / info->name();
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Saves, loads back (strict: the writer uses no key the reader would warn about), compares.
SceneFile round_trip(const Scene& scene, const std::string& path,
                     const RenderDefaults* render = nullptr) {
  save_scene_file(scene, path, render);
  SceneFile back = load_scene_file(path, SceneFileOptions{.strict = true});
  expect_same_scene(back.scene, scene);
  return back;
}

TEST(SceneFileWrite, ShippedSceneFilesRoundTrip) {
  const std::string folder = scratch_folder();
  int files = 0;
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const SceneFile original = load_scene_file(entry.path().string());
    const std::string path = folder + "/" + entry.path().filename().string();
    const SceneFile back = round_trip(original.scene, path, &original.render);
    EXPECT_EQ(back.render.width, original.render.width);
    EXPECT_EQ(back.render.height, original.render.height);
    EXPECT_EQ(back.render.exposure_ev, original.render.exposure_ev);
    EXPECT_EQ(back.render.tonemap, original.render.tonemap);
    EXPECT_EQ(back.render.brdf, original.render.brdf);
    ++files;
  }
  EXPECT_GE(files, 6);
}

// The viewer's render options and the file's description come back as given.
TEST(SceneFileWrite, RenderBlockAndDescriptionRoundTrip) {
  const std::string path = scratch_folder() + "/render_block.json";
  RenderDefaults render;
  render.exposure_ev = 1.5f;
  render.tonemap = ToneMap::clamp;
  render.brdf = Brdf::blinn_phong;
  render.energy_compensation = false;
  render.view = View::triangle;
  save_scene_file(make_sphere_grid_scene(), path, &render, "a grid, edited");
  const SceneFile back = load_scene_file(path, SceneFileOptions{.strict = true});
  EXPECT_EQ(back.description, "a grid, edited");
  EXPECT_EQ(back.render.exposure_ev, 1.5f);
  EXPECT_EQ(back.render.tonemap, ToneMap::clamp);
  EXPECT_EQ(back.render.brdf, Brdf::blinn_phong);
  EXPECT_EQ(back.render.energy_compensation, false);
  EXPECT_EQ(back.render.view, View::triangle);
}

TEST(SceneFileWrite, BuiltinScenesRoundTripAndKeepTheirShapesAndSky) {
  const std::string folder = scratch_folder();
  for (const BuiltinSceneInfo& info : builtin_scenes()) {
    SCOPED_TRACE(std::string(info.name));
    const std::string path = folder + "/" + std::string(info.name) + ".json";
    round_trip(make_builtin_scene(info.name), path);
    // Procedural shapes and the sky are written as such, not as triangles and a PFM.
    const std::string text = read_text(path);
    EXPECT_EQ(text.find("triangles"), std::string::npos);
    EXPECT_EQ(text.find(".pfm"), std::string::npos);
  }
}

TEST(SceneFileWrite, ImportedGltfModelsRoundTrip) {
  const std::string folder = scratch_folder();
  for (const std::string& model :
       {std::string("/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf"),
        kData + "/features.gltf"}) {
    SCOPED_TRACE(model);
    Scene s = import_gltf(model).scene;
    s.camera.position = {2, 3, 4};
    ASSERT_FALSE(s.textures.empty());
    const std::string path = folder + "/" + fs::path(model).stem().string() + ".json";
    round_trip(s, path);
    // Textures went to PNG files beside the scene.
    EXPECT_TRUE(fs::exists(folder + "/" + fs::path(model).stem().string() + "-texture-0.png"));
  }
}

TEST(SceneFileWrite, EditedScenesRoundTrip) {
  Scene s = make_builtin_scene("metals");
  EditHistory h;
  h.apply(s, add_sphere(s, {0.5f, 2.0f, -1.0f}, 0.3f, metal_material("brass", 0.15f)));
  h.apply(s, set_object_material(s, 0,
                                 Material{.base_color = {0.9f, 0.1f, 0.2f},
                                          .metallic = 0.3f,
                                          .roughness = 0.7f,
                                          .emissive = {0.5f, 0.25f, 0.0f}}));
  h.apply(s, move_object(s, 1,
                         glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(1.0f, 2.0f, 3.0f)) *
                             s.objects[1].transform));
  h.apply(s, delete_object(s, 2));
  round_trip(s, scratch_folder() + "/edited.json");
}

TEST(SceneFileWrite, InlineMeshesLightsAndEnvironmentsRoundTripExactly) {
  // Arbitrary floats: normals and directions normalized in float (which the reader must not
  // normalize again), tangents, angles from degrees, a non-procedural environment.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Mesh m = make_icosphere(1);
  for (glm::vec3& p : m.positions) p *= 1.0f + 0.3f * u(rng);
  for (glm::vec3& n : m.normals) n = glm::normalize(n + 0.2f * glm::vec3(u(rng), u(rng), u(rng)));
  for (glm::vec2& t : m.uvs) t += glm::vec2(u(rng), u(rng)) * 0.01f;
  m.tangents = generate_tangents(m.positions, m.normals, m.uvs, m.indices);
  Scene s;
  s.camera.position = {u(rng), u(rng), 5.0f};
  s.camera.vertical_fov = glm::radians(51.3f);
  s.camera.near_plane = 0.0123f;
  s.meshes = {m, Mesh{}};
  s.materials = {Material{.base_color = {0.1f, 0.2f, 0.3f},
                          .roughness = 0.1f,
                          .occlusion = 0.9f,
                          .normal_scale = -0.5f,
                          .double_sided = true}};
  s.objects = {Object{.transform = glm::rotate(glm::mat4(1.0f), 1.0f, glm::vec3(u(rng), 1, 0))},
               Object{.mesh = 1}};
  for (int i = 0; i < 20; ++i) {
    Light l;
    l.kind = i % 3 == 0 ? LightKind::spot : i % 3 == 1 ? LightKind::directional : LightKind::point;
    l.position = {u(rng), u(rng), u(rng)};
    l.direction = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
    l.color = glm::vec3(0.5f) + 0.5f * glm::vec3(u(rng), u(rng), u(rng));
    l.intensity = 10.0f * (1.0f + u(rng));
    l.falloff = i % 2 ? Falloff::classic : Falloff::inverse_square;
    l.range = i % 2 ? 0.0f : 4.0f + u(rng);
    l.attenuation = {1.0f, 0.1f * (1.0f + u(rng)), 0.01f};
    // Degrees to radians in single precision, as a file or a degree slider gives them: not
    // every float of radians has a float of degrees that converts to it (the header says).
    l.inner_angle = glm::radians(float(i) + 10.0f * (1.0f + u(rng)));
    l.outer_angle = glm::radians(float(i) + 40.0f + 10.0f * u(rng));
    s.lights.push_back(l);
  }
  s.background = {0.01f, 0.02f, 0.03f};
  s.ambient = {0.1f, 0.1f, 0.2f};
  Environment e;
  e.radiance.width = 8;
  e.radiance.height = 4;
  for (int i = 0; i < 32; ++i)
    e.radiance.pixels.push_back(
        glm::vec4(1.0f + u(rng), 2.0f + u(rng), 0.5f + 0.5f * u(rng), 1.0f));
  s.environment = std::make_shared<const Environment>(e);
  const std::string folder = scratch_folder();
  round_trip(s, folder + "/inline.json");
  EXPECT_TRUE(fs::exists(folder + "/inline-environment.pfm"));
  // A uniform environment is written as such.
  s.environment = std::make_shared<const Environment>(make_uniform_environment({0.5f, 1, 2}));
  round_trip(s, folder + "/uniform.json");
  EXPECT_NE(read_text(folder + "/uniform.json").find("uniform"), std::string::npos);
}

TEST(SceneFileWrite, ErrorsNameThePathOrTheField) {
  const Scene s = make_builtin_scene("spheres");
  const std::string path = "/nonexistent-folder/for/a/scene.json";
  try {
    save_scene_file(s, path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  // A value the scene model allows but the format does not: roughness above 1.
  Scene rough = s;
  rough.materials[0].roughness = 1.5f;
  const std::string folder = scratch_folder();
  try {
    save_scene_file(rough, folder + "/rough.json");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("material0.roughness"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(folder + "/rough.json"));
  // A scene that does not validate is refused before anything is written.
  Scene bad = s;
  bad.objects[0].mesh = 99;
  EXPECT_THROW(save_scene_file(bad, folder + "/bad.json"), Error);
  EXPECT_FALSE(fs::exists(folder + "/bad.json"));
}

// A save that fails says why, and leaves none of the files it wrote behind: the scene file's
// temporary a folder (refused before anything is written), or the environment's PFM a folder
// (after the texture was written). A texture file that was there before is kept.
TEST(SceneFileWrite, AFailedSaveSaysWhyAndRemovesTheFilesItWrote) {
  Scene s = make_builtin_scene("spheres");
  s.textures.push_back(
      Texture{.width = 2, .height = 1, .texels = {{255, 0, 0, 255}, {0, 0, 0, 255}}});
  Environment e;
  e.radiance.width = 4;
  e.radiance.height = 2;
  e.radiance.pixels.assign(8, glm::vec4(0.25f, 0.5f, 1.0f, 1.0f));
  e.radiance.pixels[3] = glm::vec4(2.0f);
  s.environment = std::make_shared<const Environment>(e);
  const std::string folder = scratch_folder();
  const std::string path = folder + "/ro.json";
  fs::create_directories(path + ".tmp");
  try {
    save_scene_file(s, path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write the scene file '" + path +
                                         "': its temporary file '" + path +
                                         ".tmp': it is a folder");
  }
  EXPECT_FALSE(fs::exists(folder + "/ro-texture-0.png"));
  EXPECT_FALSE(fs::exists(path));
  fs::remove(path + ".tmp");
  fs::create_directories(folder + "/ro-environment.pfm");
  EXPECT_THROW(save_scene_file(s, path), Error);
  EXPECT_FALSE(fs::exists(folder + "/ro-texture-0.png"));
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  // A texture file of an earlier save stays (it was not this save's to remove).
  std::ofstream(folder + "/ro-texture-0.png") << "earlier";
  EXPECT_THROW(save_scene_file(s, path), Error);
  EXPECT_TRUE(fs::exists(folder + "/ro-texture-0.png"));
  fs::remove(folder + "/ro-environment.pfm");
  save_scene_file(s, path);  // and with nothing in the way it saves
  EXPECT_TRUE(fs::exists(path));
}

}  // namespace
}  // namespace tessera
