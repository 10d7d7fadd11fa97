// Hierarchical depth rejection (RendererOptions::depth_rejection): it skips exactly the work
// that cannot change the image (counted against scenes whose hidden triangles are known by
// construction), never a depth tie, and leaves every bit of the visibility buffer and the image
// as rendering without it does.
#include <set>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/bench_scenes.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class DepthRejection : public test::VulkanTest {
 protected:
  struct Result {
    FrameStats stats;
    std::vector<uint64_t> visibility;
    ImageF hdr;
    std::set<uint32_t> objects;  // Scene::objects indices of the ids in the visibility buffer
  };

  Result render_with(const Scene& scene, uint32_t size, bool rejection, uint32_t tile_size = 16,
                     uint32_t samples = 1, uint32_t max_batch_triangles = 0,
                     uint32_t small_triangle_area = 64) {
    RendererOptions options;
    options.small_triangle_max_area = small_triangle_area;
    options.depth_rejection = rejection;
    options.tile_size = tile_size;
    options.max_batch_triangles = max_batch_triangles;
    Renderer renderer(context(), options);
    const Frame f = render(renderer, scene, size, size, samples);
    Result r{f.stats, f.visibility, f.hdr, {}};
    for (uint64_t key : r.visibility) {
      if (key != TS_VIS_EMPTY) r.objects.insert(renderer.object_of_triangle(uint32_t(key)));
    }
    return r;
  }
};

using tessera::testing::same_bits;

// One triangle, front-facing towards +z, reaching 10 units around the origin in x and y: from
// the default camera (z = 5, 45 degree field of view) at any depth down to z = -5 it covers
// the whole view (half-height 10 tan 22.5 = 4.1 units there).
Mesh screen_triangle() {
  Mesh m;
  m.positions = {{-10.0f, -10.0f, 0.0f}, {30.0f, -10.0f, 0.0f}, {-10.0f, 30.0f, 0.0f}};
  m.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
  m.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
  m.indices = {0, 1, 2};
  return m;
}

// A right triangle of legs 0.5 at the origin: at z = -1 (6 units from the camera, 12.9 px per
// unit in a 64 px image) its pixel box is about 7 x 7 px, under the 64 px of the small path.
Mesh small_triangle() {
  Mesh m;
  m.positions = {{0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}};
  m.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
  m.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
  m.indices = {0, 1, 2};
  return m;
}

glm::mat4 at(float x, float y, float z) {
  return glm::translate(glm::mat4(1.0f), glm::vec3(x, y, z));
}

// Object 0 covers the view at z = 0; `hidden` screen triangles lie behind it at z = -1 - 0.1 i
// and `small` small triangles at z = -1 on a grid inside the view.
Scene occluded_scene(uint32_t hidden, uint32_t small) {
  Scene s;
  s.meshes = {screen_triangle(), small_triangle()};
  s.materials = {Material{}};
  s.objects.push_back({0, 0, at(0.0f, 0.0f, 0.0f)});
  for (uint32_t i = 0; i < hidden; ++i) s.objects.push_back({0, 0, at(0, 0, -1.0f - 0.1f * i)});
  for (uint32_t i = 0; i < small; ++i) {
    s.objects.push_back({1, 0, at(-1.8f + 0.8f * (i % 5), -1.8f + 0.8f * (i / 5), -1.0f)});
  }
  return s;
}

TEST_F(DepthRejection, EveryEntryBehindATileCoveringTriangleIsSkipped) {
  // 64 x 64 px: 4 x 4 tiles of 16 px (8 x 8 of 8 px). Every screen triangle covers every tile
  // whole, so each tile lists all 21; fill lowers each tile's bound to the front triangle's
  // depth, which makes the 20 behind it rejected whatever their order in the list.
  const Scene scene = occluded_scene(20, 0);
  for (uint32_t tile : {16u, 8u}) {
    const uint32_t tiles = (64 / tile) * (64 / tile);
    const Result on = render_with(scene, 64, true, tile);
    const Result off = render_with(scene, 64, false, tile);
    EXPECT_EQ(on.stats.tile_entries, 21u * tiles) << tile;
    EXPECT_EQ(on.stats.rejected_entries, 20u * tiles) << tile;
    EXPECT_EQ(on.stats.rejected_small, 0u) << tile;
    EXPECT_EQ(off.stats.rejected_entries, 0u) << tile;
    EXPECT_EQ(on.visibility, off.visibility) << tile;
    EXPECT_TRUE(same_bits(on.hdr, off.hdr)) << tile;
    EXPECT_EQ(on.objects, std::set<uint32_t>{0}) << tile;  // the front one everywhere
  }
}

TEST_F(DepthRejection, SmallTrianglesBehindADrawnTileAreSkipped) {
  const Scene scene = occluded_scene(0, 25);
  const Result on = render_with(scene, 64, true);
  const Result off = render_with(scene, 64, false);
  EXPECT_EQ(on.stats.small_triangles, 25u);
  EXPECT_EQ(on.stats.rejected_small, 25u);
  EXPECT_EQ(off.stats.rejected_small, 0u);
  EXPECT_EQ(on.visibility, off.visibility);
  EXPECT_TRUE(same_bits(on.hdr, off.hdr));
  EXPECT_EQ(on.objects, std::set<uint32_t>{0});
  // Without the front triangle each of them is seen (nothing to hide them behind).
  Scene bare = scene;
  bare.objects.erase(bare.objects.begin());
  const Result seen = render_with(bare, 64, true);
  EXPECT_EQ(seen.stats.rejected_small, 0u);
  EXPECT_EQ(seen.objects.size(), 25u);
}

TEST_F(DepthRejection, DepthTiesAreNeverRejected) {
  // Two screen triangles in the same plane: equal depth at every sample, so the lower id wins
  // each one. Neither may be rejected by the other's bound, or the result would depend on which
  // was drawn first. Different materials make two distinct objects.
  Scene scene = occluded_scene(0, 0);
  scene.materials.push_back(Material{.base_color = glm::vec3(0.2f)});
  scene.objects.push_back({0, 1, at(0.0f, 0.0f, 0.0f)});
  const Result on = render_with(scene, 64, true);
  const Result off = render_with(scene, 64, false);
  EXPECT_EQ(on.stats.rejected_entries, 0u);
  EXPECT_EQ(on.visibility, off.visibility);
  for (uint64_t key : on.visibility) ASSERT_EQ(uint32_t(key), 0u);  // the lower of ids 0 and 1
}

TEST_F(DepthRejection, ScatterGivesTheSameBitsAtEveryTileSizeSampleCountAndBatching) {
  // Heavy overdraw in depth: the case rejection is for. Batches of 50,000 triangle instances
  // (the scene has 224,000) make later batches start from earlier ones' bounds. At 96 px every
  // triangle's box is small; only boxes up to 4 px go to the per-triangle path, so that both
  // rasterizers reject.
  const Scene scene = make_bench_scene("scatter", 1000, 16, 1.0f);
  struct Case {
    uint32_t tile, samples, batch;
  };
  for (Case c : {Case{16, 1, 0}, Case{8, 4, 0}, Case{16, 4, 50000}, Case{8, 1, 50000}}) {
    const Result on = render_with(scene, 96, true, c.tile, c.samples, c.batch, 4);
    const Result off = render_with(scene, 96, false, c.tile, c.samples, c.batch, 4);
    const std::string where = "tile " + std::to_string(c.tile) + ", " + std::to_string(c.samples) +
                              " samples, batch " + std::to_string(c.batch) + ": rejected " +
                              std::to_string(on.stats.rejected_entries) + " of " +
                              std::to_string(on.stats.tile_entries) + " entries, " +
                              std::to_string(on.stats.rejected_small) + " of " +
                              std::to_string(on.stats.small_triangles) + " small";
    SCOPED_TRACE(where);
    EXPECT_GT(on.stats.rejected_entries, 0u);
    EXPECT_GT(on.stats.rejected_small, 0u);
    EXPECT_EQ(on.visibility, off.visibility);
    EXPECT_TRUE(same_bits(on.hdr, off.hdr));
    if (c.batch > 0) {
      EXPECT_GT(on.stats.batches, 1u);
    }
  }
}

}  // namespace
}  // namespace tessera
