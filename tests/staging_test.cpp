// Uploads through a staging buffer of at most RendererOptions::staging_chunk_bytes, refilled per
// chunk (compute/renderer.cpp, submit_copies): a scene's uploads may exceed what one allocation
// holds. With chunks of 1,000 and 4,097 bytes every upload of a small scene is split, copies
// that straddle a chunk's end included, and the images must keep the bits of the default chunk
// (256 MiB, which takes each of these uploads whole): a whole upload, an edit that re-uploads
// ranges in the middle of the objects and the texels, level-of-detail chains appended after the
// vertices and indices, and the objects restored after them.
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/mesh.h"
#include "core/procedural_textures.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

using tessera::test::frame_of;
using tessera::testing::same_bits;

// A checkered floor and 300 small spheres and cubes before it, with tiled (all four maps),
// checkered and plain materials: 157 KB of uploads, 98 KB of them texels (12,286).
Scene textured_crowd() {
  Scene scene;
  scene.camera.position = {0.0f, 5.0f, 12.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.textures.push_back(
      make_checker_texture(64, 8, glm::vec3(0.8f), glm::vec3(0.05f)));  // texture 0
  const TileMaps tiles = make_tile_maps(32, 4, {0.75f, 0.45f, 0.3f}, 1.5f);
  for (const Texture& t :
       {tiles.base_color, tiles.metallic_roughness, tiles.normal, tiles.occlusion})
    scene.textures.push_back(t);  // textures 1 to 4
  scene.textures.push_back(make_checker_texture(32, 4, glm::vec3(1.0f), glm::vec3(0.3f)));  // 5
  Material floor;
  floor.base_color_map = 0;
  Material tiled;
  tiled.roughness = 1.0f;
  tiled.base_color_map = 1;
  tiled.metallic_roughness_map = 2;
  tiled.normal_map = 3;
  tiled.occlusion_map = 4;
  Material copper;
  copper.base_color = {0.95f, 0.64f, 0.54f};
  copper.metallic = 1.0f;
  copper.roughness = 0.3f;
  copper.base_color_map = 5;
  Material blue;
  blue.base_color = {0.2f, 0.5f, 0.9f};
  scene.materials = {floor, tiled, copper, blue};
  scene.meshes = {make_plane(2, 2), make_uv_sphere(12, 6), make_cube()};
  Object ground;
  ground.transform =
      glm::scale(glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), {1, 0, 0}), glm::vec3(10.0f));
  scene.objects.push_back(ground);
  for (uint32_t i = 0; i < 300; ++i) {
    Object o;
    o.mesh = 1 + i % 2;
    o.material = 1 + i % 3;
    const glm::vec3 at(-7.0f + 0.7f * float(i % 20), 0.3f, -6.0f + 0.8f * float(i / 20));
    o.transform = glm::scale(glm::translate(glm::mat4(1.0f), at), glm::vec3(0.25f));
    scene.objects.push_back(o);
  }
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = {-0.5f, -0.8f, -0.6f};
  sun.intensity = 2.5f;
  Light lamp;
  lamp.position = {1.5f, 3.0f, 3.0f};
  lamp.intensity = 12.0f;
  scene.lights = {sun, lamp};
  scene.ambient = glm::vec3(0.08f);
  return scene;
}

struct Uploaded {
  std::vector<uint64_t> bytes;  // of each set_scene
  std::vector<ImageF> hdr;      // of each frame
  std::vector<Image8> ldr;
};

Uploaded upload_and_render(Context& ctx, uint64_t chunk) {
  RendererOptions options;
  options.staging_chunk_bytes = chunk;
  Renderer renderer(ctx, options);
  Uploaded out;
  FrameSettings frame = frame_of(96, 72);
  const auto shoot = [&] {
    renderer.render(frame);
    out.hdr.push_back(renderer.read_hdr());
    out.ldr.push_back(renderer.read_ldr());
  };
  Scene scene = textured_crowd();
  out.bytes.push_back(renderer.set_scene(scene).bytes);
  shoot();
  // Ranges in the middle: one object moved (among the others, so a run of objects in the
  // numbering changes), the last texture recoloured (after the other textures' texels).
  scene.objects[150].transform = glm::translate(scene.objects[150].transform, {0.0f, 4.0f, 0.0f});
  scene.textures[5] = make_checker_texture(32, 4, {1.0f, 0.2f, 0.2f}, glm::vec3(0.0f));
  out.bytes.push_back(renderer.set_scene(scene).bytes);
  shoot();
  frame.lod = Lod::automatic;  // the chains, uploaded after the vertices and indices
  shoot();
  frame.lod = Lod::off;  // the objects' own triangles, uploaded again
  shoot();
  return out;
}

class Staging : public test::VulkanTest {};

TEST_F(Staging, ChunksOfAnySizeGiveTheSameImages) {
  const Uploaded whole = upload_and_render(context(), RendererOptions{}.staging_chunk_bytes);
  ASSERT_EQ(whole.bytes.size(), 2u);
  // Each upload spans many chunks of either size.
  EXPECT_GT(whole.bytes[0], 20u * 4097u);
  EXPECT_GT(whole.bytes[1], 2u * 4097u);
  EXPECT_NE(whole.ldr[1].pixels, whole.ldr[0].pixels);  // the edit shows
  EXPECT_NE(whole.ldr[2].pixels, whole.ldr[1].pixels);  // coarser levels show
  EXPECT_EQ(whole.ldr[3].pixels, whole.ldr[1].pixels);
  for (const uint64_t chunk : {uint64_t(1000), uint64_t(4097)}) {
    SCOPED_TRACE("chunk " + std::to_string(chunk));
    const Uploaded split = upload_and_render(context(), chunk);
    EXPECT_EQ(split.bytes, whole.bytes);
    ASSERT_EQ(split.hdr.size(), whole.hdr.size());
    for (size_t i = 0; i < whole.hdr.size(); ++i) {
      SCOPED_TRACE("frame " + std::to_string(i));
      EXPECT_TRUE(same_bits(split.hdr[i], whole.hdr[i]));
      EXPECT_EQ(split.ldr[i].pixels, whole.ldr[i].pixels);
    }
  }
}

TEST_F(Staging, AChunkOfNoBytesIsRefused) {
  RendererOptions options;
  options.staging_chunk_bytes = 0;
  try {
    Renderer renderer(context(), options);
    FAIL() << "a chunk of 0 bytes was accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "staging chunk must be at least 1 byte");
  }
}

}  // namespace
}  // namespace tessera
