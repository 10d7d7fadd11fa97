// Bad scenes are rejected with a message that names the problem, before anything reaches the GPU.
#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/mesh.h"
#include "shaders/shared/gpu_types.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

Scene one_triangle_scene() {
  Scene s;
  Mesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  m.uvs = {{0, 0}, {1, 0}, {0, 1}};
  m.indices = {0, 1, 2};
  s.meshes.push_back(m);
  s.materials.push_back({});
  s.objects.push_back({});
  return s;
}

std::string error_of(const Scene& s) {
  try {
    validate_scene(s);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SceneValidation, AcceptsBuiltinScenes) {
  for (const auto& info : builtin_scenes()) EXPECT_EQ(error_of(make_builtin_scene(info.name)), "");
}

// The field of view a scene file allows, (0, 179] degrees (docs/scene-format.md), as it arrives
// after the file's conversion to radians.
TEST(SceneValidation, AcceptsTheFieldOfViewScenesFilesAllow) {
  Scene s = one_triangle_scene();
  s.camera.vertical_fov = float(179.0 * 3.14159265358979323846 / 180.0);
  EXPECT_EQ(error_of(s), "");
  s.camera.vertical_fov = float(179.5 * 3.14159265358979323846 / 180.0);
  EXPECT_NE(error_of(s).find("must be in (0, 179] degrees"), std::string::npos) << error_of(s);
}

TEST(SceneValidation, NamesNonFiniteVertex) {
  Scene s = one_triangle_scene();
  s.meshes[0].positions[1].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(error_of(s).find("mesh 0 vertex 1"), std::string::npos) << error_of(s);
  s = one_triangle_scene();
  s.meshes[0].positions[2].x = std::numeric_limits<float>::infinity();
  EXPECT_NE(error_of(s).find("mesh 0 vertex 2"), std::string::npos) << error_of(s);
}

TEST(SceneValidation, SecondUvSetIsCheckedWhereMaterialsReadIt) {
  Scene s = one_triangle_scene();
  s.meshes[0].uvs1 = {{0, 0}, {1, 0}};
  EXPECT_NE(error_of(s).find("mesh 0 has 2 uvs of set 1 for 3 positions"), std::string::npos)
      << error_of(s);
  s.meshes[0].uvs1.push_back({0, std::numeric_limits<float>::infinity()});
  EXPECT_NE(error_of(s).find("mesh 0 vertex 2 has a NaN or infinite uv of set 1"),
            std::string::npos)
      << error_of(s);
  s = one_triangle_scene();
  s.materials[0].uv1_maps = TS_MAP_BASE_COLOR;
  EXPECT_NE(error_of(s).find("object 0: material 0 reads uv set 1, which mesh 0 does not have"),
            std::string::npos)
      << error_of(s);
  s.meshes[0].uvs1 = s.meshes[0].uvs;
  EXPECT_EQ(error_of(s), "");
  s.materials[0].uv1_maps = 32;
  EXPECT_NE(error_of(s).find("material 0 has uv1_maps 32"), std::string::npos) << error_of(s);
}

TEST(SceneValidation, NamesOutOfRangeReferences) {
  Scene s = one_triangle_scene();
  s.meshes[0].indices[2] = 7;
  EXPECT_NE(error_of(s).find("index 2 is 7"), std::string::npos) << error_of(s);
  s = one_triangle_scene();
  s.objects[0].mesh = 3;
  EXPECT_NE(error_of(s).find("object 0 uses mesh 3"), std::string::npos) << error_of(s);
  s = one_triangle_scene();
  s.objects[0].material = 1;
  EXPECT_NE(error_of(s).find("object 0 uses material 1"), std::string::npos) << error_of(s);
  s = one_triangle_scene();
  s.meshes[0].indices.pop_back();
  EXPECT_NE(error_of(s).find("not a multiple of 3"), std::string::npos) << error_of(s);
}

TEST(SceneValidation, NamesBadTransformCameraAndLights) {
  Scene s = one_triangle_scene();
  s.objects[0].transform[3][0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(error_of(s).find("object 0 has a NaN"), std::string::npos) << error_of(s);
  s = one_triangle_scene();
  s.camera.target = s.camera.position;
  EXPECT_NE(error_of(s).find("target equals its position"), std::string::npos) << error_of(s);
  s = one_triangle_scene();
  s.camera.near_plane = 0.0f;
  EXPECT_NE(error_of(s).find("near plane"), std::string::npos) << error_of(s);
  s = one_triangle_scene();
  s.materials[0].occlusion = 1.5f;
  EXPECT_NE(error_of(s).find("occlusion outside [0, 1]"), std::string::npos) << error_of(s);
  s = one_triangle_scene();
  s.materials[0].emissive = {0.0f, -1.0f, 0.0f};
  EXPECT_NE(error_of(s).find("negative emissive"), std::string::npos) << error_of(s);
  s = one_triangle_scene();
  s.lights.push_back({});
  s.lights[0].intensity = std::numeric_limits<float>::infinity();
  EXPECT_NE(error_of(s).find("light 0"), std::string::npos) << error_of(s);
}

class SceneUpload : public test::VulkanTest {};

TEST_F(SceneUpload, RendererRejectsBadSceneAndBadSizes) {
  Renderer renderer(context());
  Scene bad = one_triangle_scene();
  bad.meshes[0].normals[0].z = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(renderer.set_scene(bad), Error);
  FrameSettings settings;
  EXPECT_THROW(renderer.render(settings), Error) << "render before any scene was set";
  renderer.set_scene(one_triangle_scene());
  // Sizes are refused as ImageSizeError, which the tool tells apart (a bad --size).
  settings.width = 0;
  EXPECT_THROW(renderer.render(settings), ImageSizeError);
  settings.width = 20000;
  EXPECT_THROW(renderer.render(settings), ImageSizeError);
  // 8192 x 8192 needs a 512 MiB visibility buffer, over lavapipe's 128 MiB storage range, which
  // holds 2^27 / 8 = 2^24 keys of 8 bytes: a square of 4096 px a side at 1 sample, of 2048 at 4.
  settings.width = settings.height = 8192;
  try {
    renderer.render(settings);
    ADD_FAILURE() << "8192x8192 should not fit lavapipe";
  } catch (const ImageSizeError& e) {
    EXPECT_EQ(e.width, 8192u);
    EXPECT_EQ(e.reason,
              "needs a 512 MiB visibility buffer, more than this device's maxStorageBufferRange "
              "(128 MiB): it takes at most 16777216 pixels at 1 sample, e.g. 4096x4096");
  }
  settings.width = settings.height = 4096;
  settings.samples = 4;
  try {
    renderer.render(settings);
    ADD_FAILURE() << "4096x4096 at 4 samples should not fit lavapipe";
  } catch (const ImageSizeError& e) {
    EXPECT_NE(e.reason.find("at 4 samples needs a 512 MiB visibility buffer"), std::string::npos)
        << e.reason;
    EXPECT_NE(e.reason.find("at most 4194304 pixels at 4 samples, e.g. 2048x2048"),
              std::string::npos)
        << e.reason;
  }
}

TEST_F(SceneUpload, UploadsOnlyWhatChanged) {
  Renderer renderer(context());
  Scene scene = make_sphere_grid_scene();
  UploadStats first = renderer.set_scene(scene);
  uint64_t all_bytes = scene.objects.size() * sizeof(tessera::gpu::GpuObject) +
                       scene.materials.size() * sizeof(tessera::gpu::GpuMaterial) +
                       scene.lights.size() * sizeof(tessera::gpu::GpuLight);
  // Per index, its word and the adjacency word of its edge (TS_BINDING_ADJACENCY).
  for (const Mesh& m : scene.meshes) {
    all_bytes += m.positions.size() * sizeof(tessera::gpu::GpuVertex) +
                 m.indices.size() * 2 * sizeof(uint32_t);
  }
  // After the objects, a word per TS_TRIANGLE_GROUP triangle instances (the group table).
  uint64_t instances = 0;
  for (const Object& o : scene.objects) instances += scene.meshes[o.mesh].triangle_count();
  all_bytes += (instances + TS_TRIANGLE_GROUP - 1) / TS_TRIANGLE_GROUP * sizeof(uint32_t);
  EXPECT_EQ(first.bytes, all_bytes) << "the first upload copies everything";
  EXPECT_EQ(renderer.set_scene(scene).bytes, 0u) << "an unchanged scene uploads nothing";

  scene.materials[10].roughness = 0.77f;
  UploadStats one_material = renderer.set_scene(scene);
  EXPECT_EQ(one_material.bytes, sizeof(tessera::gpu::GpuMaterial)) << "one GpuMaterial";
  EXPECT_EQ(one_material.buffers_created, 0u);

  scene.lights[2].intensity = 10.0f;
  EXPECT_EQ(renderer.set_scene(scene).bytes, sizeof(tessera::gpu::GpuLight)) << "one GpuLight";

  FrameSettings settings;
  settings.width = settings.height = 64;
  renderer.render(settings);  // and it still renders after partial updates
}

TEST_F(SceneUpload, RebuildsOnlyTheMipChainsOfChangedTextures) {
  Scene scene = make_textured_scene();
  ASSERT_EQ(scene.textures.size(), 6u) << "six distinct textures (core/builtin_scenes.cpp)";
  FrameSettings settings;
  settings.width = settings.height = 96;
  Renderer renderer(context());
  EXPECT_EQ(renderer.set_scene(scene).mip_chains_built, 6u) << "nothing cached yet";
  EXPECT_EQ(renderer.set_scene(scene).mip_chains_built, 0u) << "unchanged textures";
  renderer.render(settings);

  // A texel of texture 5 (the second checker) changes: only its chain is built again.
  scene.textures[5].texels[17] = glm::u8vec4(200, 10, 30, 255);
  EXPECT_EQ(renderer.set_scene(scene).mip_chains_built, 1u);
  renderer.render(settings);
  const ImageF cached = renderer.read_hdr();

  Renderer fresh(context());
  EXPECT_EQ(fresh.set_scene(scene).mip_chains_built, 6u);
  fresh.render(settings);
  const ImageF built = fresh.read_hdr();
  ASSERT_EQ(cached.pixels.size(), built.pixels.size());
  EXPECT_EQ(std::memcmp(cached.pixels.data(), built.pixels.data(),
                        built.pixels.size() * sizeof(glm::vec4)),
            0)
      << "reused chains give the image of chains built from scratch";

  // The same content twice in one scene is built once; flipping the sRGB flag is a change.
  scene.textures.push_back(scene.textures[0]);
  EXPECT_EQ(renderer.set_scene(scene).mip_chains_built, 0u);
  scene.textures[6].srgb = !scene.textures[6].srgb;
  EXPECT_EQ(renderer.set_scene(scene).mip_chains_built, 1u);
}

}  // namespace
}  // namespace tessera
