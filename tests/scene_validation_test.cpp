// Bad scenes are rejected with a message that names the problem, before anything reaches the GPU.
#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "compute/scene_upload.h"
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

std::string buffer_error(const SceneBufferCounts& counts, uint64_t max_range,
                         const std::string& what = "the scene") {
  try {
    check_scene_buffers(counts, max_range, what);
  } catch (const SceneSizeError& e) {
    return e.what();
  }
  return "";
}

// Every storage buffer of the scene is bound whole, so none may exceed maxStorageBufferRange.
TEST(SceneBuffers, EachIsCheckedAgainstTheStorageRange) {
  constexpr uint64_t kLavapipe = 128ull << 20;  // lavapipe's maxStorageBufferRange, 2^27
  // 10^6 objects of 160 bytes: 160e6 / 2^20 = 152.6 MiB; 2^27 / 160 = 838860.8 objects fit.
  EXPECT_EQ(buffer_error({.objects = 1000000}, kLavapipe),
            "the scene needs a 153 MiB object buffer (1000000 objects), more than this device's "
            "maxStorageBufferRange (128 MiB): it holds at most 838860 objects");
  EXPECT_EQ(buffer_error({.objects = 838860}, kLavapipe), "") << "838860 * 160 < 2^27";
  // 2^27 / 48 = 2796202.7 vertices; one more is 134217744 bytes, 16 over.
  EXPECT_EQ(buffer_error({.vertices = 2796202}, kLavapipe), "");
  EXPECT_EQ(buffer_error({.vertices = 2796203}, kLavapipe),
            "the scene needs a 129 MiB vertex buffer (2796203 vertices), more than this device's "
            "maxStorageBufferRange (128 MiB): it holds at most 2796202 vertices");

  // A small limit (sizes in bytes below 1 MiB), at exactly the limit and one word over.
  EXPECT_EQ(buffer_error({.indices = 250}, 1000), "");
  EXPECT_EQ(buffer_error({.indices = 251}, 1000),
            "the scene needs an index buffer of 1004 bytes (251 indices), more than this "
            "device's maxStorageBufferRange (1000 bytes): it holds at most 250 indices");
  // The group table follows the objects: 6 * 160 + 10 * 4 = 1000 fits, 11 words do not, and
  // the 5 objects the message names are 1000 * 6 / 1004 = 5.98 objects like these.
  EXPECT_EQ(buffer_error({.objects = 6, .group_objects = 10}, 1000), "");
  EXPECT_EQ(buffer_error({.objects = 6, .group_objects = 11}, 1000),
            "the scene needs an object buffer of 1004 bytes (6 objects), more than this device's "
            "maxStorageBufferRange (1000 bytes): it holds at most 5 objects");
  // Each other buffer by its element's size: 80-byte materials, lights and textures, 8-byte
  // uv set 1 entries, 16-byte and 32-byte level-of-detail entries. (Not the texels, which the
  // shaders read at a device address: TexelsAreCheckedAgainstTheAllocationLimits.)
  EXPECT_NE(buffer_error({.materials = 13}, 1000).find("material buffer of 1040 bytes"),
            std::string::npos);
  EXPECT_NE(buffer_error({.lights = 13}, 1000).find("light buffer of 1040 bytes"),
            std::string::npos);
  EXPECT_NE(buffer_error({.textures = 13}, 1000).find("texture buffer of 1040 bytes"),
            std::string::npos);
  EXPECT_NE(buffer_error({.uv1s = 126}, 1000).find("uv set 1 buffer of 1008 bytes"),
            std::string::npos);
  EXPECT_NE(buffer_error({.lod_levels = 63}, 1000).find("level buffer of 1008 bytes"),
            std::string::npos);
  EXPECT_NE(buffer_error({.lod_meshes = 32}, 1000).find("mesh buffer of 1024 bytes"),
            std::string::npos);
  EXPECT_EQ(buffer_error({.materials = 12, .lights = 12, .textures = 12}, 1000), "");
  // The first buffer over is named; the caller says what needs it.
  EXPECT_EQ(buffer_error({.vertices = 21, .indices = 251}, 1000,
                         "the scene with its level-of-detail chains")
                .rfind("the scene with its level-of-detail chains needs a vertex buffer of 1008 "
                       "bytes (21 vertices)",
                       0),
            0u);
  try {
    check_scene_buffers({.objects = 1000000}, kLavapipe);
    ADD_FAILURE() << "10^6 objects should not fit 128 MiB";
  } catch (const SceneSizeError& e) {
    EXPECT_EQ(e.buffer, "object buffer");
    EXPECT_EQ(e.bytes, 160000000u);
    EXPECT_EQ(e.limit, kLavapipe);
  }
}

std::string texel_error(uint64_t texels, const AddressedBufferLimits& limits) {
  try {
    check_texel_buffer(texels, limits);
  } catch (const SceneSizeError& e) {
    return e.what();
  }
  return "";
}

// The texel buffer is read at its device address, not bound by a descriptor: the device's
// largest allocation and buffer and its memory cap it, not maxStorageBufferRange.
TEST(SceneBuffers, TexelsAreCheckedAgainstTheAllocationLimits) {
  // lavapipe's: maxMemoryAllocationSize 2 GiB, maxBufferSize 4 GiB - 1, and a larger heap.
  const AddressedBufferLimits lavapipe{
      .max_allocation = 1ull << 31, .max_buffer = 0xFFFFFFFFull, .heap = 16ull << 30};
  // A 4096 x 4096 texture's chain has (4^13 - 1) / 3 = 22369621 texels, 178956968 bytes: over
  // the 128 MiB of lavapipe's maxStorageBufferRange, which refused it before, and well within
  // 2 GiB, which holds 2^31 / 8 = 268435456 texels.
  EXPECT_EQ(texel_error(22369621, lavapipe), "");
  EXPECT_EQ(texel_error(268435456, lavapipe), "");
  // A 16384 x 16384 texture's: (4^15 - 1) / 3 = 357913941 texels, 2863311528 bytes, 2730.7 MiB.
  EXPECT_EQ(texel_error(357913941, lavapipe),
            "the scene needs a 2731 MiB texel buffer (357913941 texels with their mip levels), "
            "more than this device's maxMemoryAllocationSize (2048 MiB): it holds at most "
            "268435456 texels");
  // Whichever limit is smallest is named: 126 texels are 1008 bytes, 125 fit 1000.
  EXPECT_EQ(texel_error(125, {.max_allocation = 4000, .max_buffer = 1000, .heap = 8000}), "");
  EXPECT_EQ(texel_error(126, {.max_allocation = 4000, .max_buffer = 1000, .heap = 8000}),
            "the scene needs a texel buffer of 1008 bytes (126 texels with their mip levels), "
            "more than this device's maxBufferSize (1000 bytes): it holds at most 125 texels");
  EXPECT_NE(texel_error(126, {.max_allocation = 4000, .max_buffer = 8000, .heap = 1000})
                .find("more than this device's largest device-local memory heap (1000 bytes)"),
            std::string::npos);
  try {
    check_texel_buffer(357913941, lavapipe);
    ADD_FAILURE() << "2863311528 bytes should not fit 2 GiB";
  } catch (const SceneSizeError& e) {
    EXPECT_EQ(e.buffer, "texel buffer");
    EXPECT_EQ(e.bytes, 2863311528u);
    EXPECT_EQ(e.limit, 1ull << 31);
  }
}

TEST(SceneBuffers, CountsAreTheFlattenedArrays) {
  Scene s = one_triangle_scene();
  s.objects.push_back({});
  const SceneBufferCounts c = buffer_counts(flatten_scene(s));
  EXPECT_EQ(c.vertices, 3u);
  EXPECT_EQ(c.indices, 3u);
  EXPECT_EQ(c.objects, 2u);
  EXPECT_EQ(c.group_objects, 1u) << "2 triangle instances, one group";
  EXPECT_EQ(c.materials, 1u);
  EXPECT_EQ(c.uv1s, 0u) << "no material reads uv set 1";
}

TEST(SceneBuffers, TooManyTriangleInstancesNamesTheMeshThatMakesThem) {
  // 2^16 - 1 triangles (a plane of 1 x (2^15 - 1) quads is 2^16 - 2: one triangle more by hand)
  // placed by 2^16 + 2 objects: (2^16 - 1)(2^16 + 2) = 2^32 + 2^16 - 2 > 2^32 - 1. A second
  // mesh of one triangle placed once comes after.
  Scene s = one_triangle_scene();
  Mesh big;
  const uint32_t triangles = 65535;
  for (uint32_t t = 0; t < triangles; ++t) {
    big.indices.insert(big.indices.end(), {0, 1, 2});
  }
  big.positions = s.meshes[0].positions;
  big.normals = s.meshes[0].normals;
  big.uvs = s.meshes[0].uvs;
  s.meshes.insert(s.meshes.begin(), big);
  s.objects[0].mesh = 1;
  for (uint32_t i = 0; i < 65538; ++i) s.objects.push_back({.mesh = 0});
  try {
    flatten_scene(s);
    ADD_FAILURE() << "over 2^32 - 1 triangle instances";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "the scene has 4295032831 triangle instances, more than the 2^32 - 1 Tessera can "
              "number: 4295032830 of them are the 65535 triangles of mesh 0, which 65538 objects "
              "place");
  }
}

class SceneUpload : public test::VulkanTest {};

// Lowers the context's maxStorageBufferRange (what the renderer reads; the validation layer
// keeps the device's own) while it lives.
struct LoweredStorageRange {
  LoweredStorageRange(Context& ctx, uint32_t range)
      : limits(ctx.properties.limits), saved(limits.maxStorageBufferRange) {
    limits.maxStorageBufferRange = range;
  }
  ~LoweredStorageRange() { limits.maxStorageBufferRange = saved; }
  VkPhysicalDeviceLimits& limits;
  uint32_t saved;
};

// set_camera renders what set_scene with only the camera changed renders, bit for bit, and
// refuses what validate_scene refuses in a camera.
TEST_F(SceneUpload, SetCameraRendersAsSetSceneWithThatCamera) {
  Scene scene = make_sphere_grid_scene();
  FrameSettings settings;
  settings.width = 64;
  settings.height = 48;
  Camera moved = scene.camera;
  moved.position = glm::vec3(3.0f, 2.0f, 7.0f);
  Renderer orbiting(context());
  orbiting.set_scene(scene);
  orbiting.render(settings);
  orbiting.set_camera(moved);
  orbiting.render(settings);
  scene.camera = moved;
  Renderer fresh(context());
  fresh.set_scene(scene);
  fresh.render(settings);
  EXPECT_EQ(orbiting.read_hdr().pixels, fresh.read_hdr().pixels);
  Camera broken = moved;
  broken.target = broken.position;  // no view direction
  EXPECT_THROW(orbiting.set_camera(broken), Error);
}

TEST_F(SceneUpload, SceneOverTheStorageRangeIsRefusedBeforeUploadAndKeepsThePrevious) {
  Renderer renderer(context());
  FrameSettings settings;
  settings.width = settings.height = 8;
  renderer.set_scene(one_triangle_scene());
  renderer.render(settings);
  const Image8 before = renderer.read_ldr();
  // 40 objects of the triangle: 40 * 160 bytes and a group word, 6404 bytes, over 4800, which
  // holds 4800 * 40 / 6404 = 29.98 such objects.
  Scene many = one_triangle_scene();
  many.objects.assign(40, Object{});
  {
    LoweredStorageRange lowered(context(), 4800);
    try {
      renderer.set_scene(many);
      ADD_FAILURE() << "6404 bytes of objects should not fit 4800";
    } catch (const SceneSizeError& e) {
      EXPECT_EQ(std::string(e.what()),
                "the scene needs an object buffer of 6404 bytes (40 objects), more than this "
                "device's maxStorageBufferRange (4800 bytes): it holds at most 29 objects");
    }
  }
  renderer.render(settings);
  EXPECT_EQ(renderer.read_ldr().pixels, before.pixels) << "the previous scene stays";

  // The level-of-detail chains are checked as the first frame with them appends them: a
  // 32-segment sphere's 33 * 17 vertices (26928 bytes) fit 30000 bytes, its chain's other
  // tessellations after them do not. The refused frame leaves the scene as it was.
  Scene sphere = one_triangle_scene();
  sphere.meshes[0] = make_uv_sphere(32, 16);
  sphere.camera.position = {0.0f, 0.0f, 4.0f};
  sphere.lights.push_back({.position = {2.0f, 2.0f, 4.0f}, .intensity = 20.0f});
  renderer.set_scene(sphere);
  renderer.render(settings);
  const Image8 without_lod = renderer.read_ldr();
  settings.lod = Lod::automatic;
  {
    LoweredStorageRange lowered(context(), 30000);
    try {
      renderer.render(settings);
      ADD_FAILURE() << "the chains' vertices should not fit 30000 bytes";
    } catch (const SceneSizeError& e) {
      EXPECT_EQ(e.buffer, "vertex buffer");
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("the scene with its level-of-detail chains needs a ", 0), 0u)
          << message;
      EXPECT_NE(message.find(" vertex buffer ("), std::string::npos) << message;
      EXPECT_NE(message.find("maxStorageBufferRange (30000 bytes): it holds at most 625 vertices"),
                std::string::npos)
          << message << " (30000 / 48 = 625)";
    }
  }
  settings.lod = Lod::off;
  renderer.render(settings);
  EXPECT_EQ(renderer.read_ldr().pixels, without_lod.pixels);
  settings.lod = Lod::automatic;
  renderer.render(settings);
  const Image8 with_lod = renderer.read_ldr();
  Renderer fresh(context());
  fresh.set_scene(sphere);
  fresh.render(settings);
  EXPECT_EQ(fresh.read_ldr().pixels, with_lod.pixels) << "the chains appended once, as anew";
}

// The texels are read at a buffer device address, not through a descriptor: a scene whose
// texel buffer exceeds maxStorageBufferRange renders, and as it does under the device's own
// range, to the bit.
TEST_F(SceneUpload, TexelsPastTheStorageRangeRender) {
  const Scene scene = make_builtin_scene("textured");
  // Textures of 1024 x 1024, four of 512 x 512 and one of 256 x 256 with their mip chains:
  // (4^11 - 1) / 3 + 4 (4^10 - 1) / 3 + (4^9 - 1) / 3 = 1398101 + 1398100 + 87381 texels,
  // 23068656 bytes, over 1 MiB, which every other buffer of the scene fits.
  constexpr uint32_t kRange = 1u << 20;
  const GpuSceneArrays arrays = flatten_scene(scene);
  ASSERT_EQ(arrays.texels.size(), 2883582u);
  ASSERT_NO_THROW(check_scene_buffers(buffer_counts(arrays), kRange));
  FrameSettings settings;
  settings.width = 64;
  settings.height = 48;
  Renderer normal(context());
  normal.set_scene(scene);
  normal.render(settings);
  const ImageF expected = normal.read_hdr();
  LoweredStorageRange lowered(context(), kRange);
  Renderer renderer(context());
  renderer.set_scene(scene);
  renderer.render(settings);
  const ImageF image = renderer.read_hdr();
  ASSERT_EQ(image.pixels.size(), expected.pixels.size());
  EXPECT_EQ(std::memcmp(image.pixels.data(), expected.pixels.data(),
                        image.pixels.size() * sizeof(image.pixels[0])),
            0);
}

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

// Floats between 2^k and 2^(k+1) are 2^(k-23) apart. A cube of side 2 (make_cube) is resolved
// coarsely where that spacing exceeds 2/1024 = 2^-9: from 2^15 on (2^-8), not below (2^-9 at
// 2^14..2^15, equal, not above).
TEST(CoarsePositions, ObjectsFarForTheirSizeAreFoundByFloatSpacing) {
  Scene scene;
  scene.meshes.push_back(make_cube());
  scene.materials.push_back(Material{});
  const auto place = [&](glm::vec3 at, float scale) {
    Object o;
    o.transform = glm::scale(glm::translate(glm::mat4(1.0f), at), glm::vec3(scale));
    scene.objects.push_back(o);
  };
  place({0.0f, 0.0f, 0.0f}, 1.0f);
  place({20000.0f, 0.0f, 0.0f}, 1.0f);  // reaches 20001: spacing 2^-9, not above 2^-9
  EXPECT_EQ(coarse_positions(scene).count, 0u);
  place({0.0f, -40000.0f, 0.0f}, 1.0f);  // reaches 40001: spacing 2^-8
  place({1e6f, 0.0f, 0.0f}, 1.0f);       // 2^-4 = 0.0625
  place({1e6f, 0.0f, 0.0f}, 100.0f);     // side 200: 0.0625 is not above 200/1024
  const CoarsePositions coarse = coarse_positions(scene);
  EXPECT_EQ(coarse.count, 2u);
  EXPECT_EQ(coarse.first, 2u);
  EXPECT_DOUBLE_EQ(coarse.distance, 40001.0);
  EXPECT_DOUBLE_EQ(coarse.spacing, 1.0 / 256.0);
  EXPECT_DOUBLE_EQ(coarse.size, 2.0);
}

}  // namespace
}  // namespace tessera
