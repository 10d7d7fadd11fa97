// Tile lists (RendererOptions::tile_lists): direct lists, a fixed room per tile written by the
// fill pass without a count or a scan, give the image and counts that counted lists give, grow
// when a list overflows its room, and under TileLists::automatic give way to counted lists
// when their room would take too much memory. The entry counts are checked against scenes whose
// lists are known by hand.
#include <string>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

using tessera::test::frame_of;
using tessera::testing::same_bits;

// A unit square in the xy plane from the origin, facing +z: two triangles.
Mesh unit_square() {
  Mesh m;
  m.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  m.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
  m.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// `count` squares of side `side` units with their lower left corner at (x, y), stacked from
// z = -1 away from the default camera (z = 5, 45 degree vertical field of view) in steps of
// `step`.
Scene stacked_squares(uint32_t count, float x, float y, float side, float step) {
  Scene scene;
  scene.meshes = {unit_square()};
  scene.materials = {Material{}};
  for (uint32_t i = 0; i < count; ++i) {
    const glm::mat4 at = glm::translate(glm::mat4(1.0f), glm::vec3(x, y, -1.0f - step * float(i)));
    scene.objects.push_back({0, 0, glm::scale(at, glm::vec3(side, side, 1.0f))});
  }
  return scene;
}

class TileLists : public test::VulkanTest {
 protected:
  // Renders `scene` with counted and with direct tile lists (the same options otherwise) and
  // expects the same visibility buffer, images and list entries; returns the direct frame.
  Frame expect_same_image(const Scene& scene, const FrameSettings& settings,
                          RendererOptions options, const std::string& what) {
    SCOPED_TRACE(what);
    options.tile_lists = tessera::TileLists::counted;
    Renderer counted_renderer(context(), options);
    const Frame counted = render(counted_renderer, scene, settings);
    options.tile_lists = tessera::TileLists::direct;
    Renderer direct_renderer(context(), options);
    const Frame direct = render(direct_renderer, scene, settings);
    EXPECT_EQ(counted.stats.tile_list_stride, 0u);
    EXPECT_GT(direct.stats.tile_list_stride, 0u);
    EXPECT_EQ(direct.stats.tile_entries, counted.stats.tile_entries);
    EXPECT_EQ(direct.stats.big_triangles, counted.stats.big_triangles);
    EXPECT_EQ(direct.stats.small_triangles, counted.stats.small_triangles);
    EXPECT_EQ(direct.visibility, counted.visibility);
    EXPECT_TRUE(same_bits(direct.hdr, counted.hdr));
    EXPECT_EQ(direct.ldr.pixels, counted.ldr.pixels);
    return direct;
  }
};

TEST_F(TileLists, DirectListsGiveTheCountedListsImage) {
  // Boxes over 1 px are binned, so most of each scene's triangles go through the lists: the
  // textured scene's floor reaches the horizon (clipped triangles are binned too).
  RendererOptions binned{.small_triangle_max_area = 1};
  for (const char* name : {"spheres", "textured", "lights"}) {
    const Frame direct =
        expect_same_image(make_builtin_scene(name), frame_of(200, 150), binned, name);
    EXPECT_GT(direct.stats.tile_entries, 0u) << name;
  }
  const Scene spheres = make_builtin_scene("spheres");
  RendererOptions tiles_of_8 = binned;
  tiles_of_8.tile_size = 8;
  expect_same_image(spheres, frame_of(96, 80, 4), tiles_of_8, "tiles of 8, 4 samples");
  RendererOptions batches = binned;
  batches.max_batch_triangles = 2000;  // each batch fills and rasterizes its own lists
  const Frame batched = expect_same_image(spheres, frame_of(64, 64), batches, "batches");
  EXPECT_GT(batched.stats.batches, 1u);
  RendererOptions no_rejection = binned;
  no_rejection.depth_rejection = false;
  expect_same_image(spheres, frame_of(64, 64), no_rejection, "without depth rejection");
}

TEST_F(TileLists, AListLongerThanItsRoomGrowsTheRoom) {
  // 64 x 64 px, tiles of 16. The default camera sees 12.9 px per unit at z = -1 (6 units
  // away: 32 / (6 tan 22.5 deg)), the origin at pixel (32, 32); 11.8 px per unit at the
  // farthest square (6.5 units). So squares from (-1, 0.3) to (-0.3, 1) units cover pixels
  // 19-29 across and down at most: inside tile (1, 1) (pixels 16-31) alone. Each square's two
  // triangles are binned (boxes over 1 px), one entry each in that tile's list: 20 squares
  // make one list of 40.
  const Scene scene = stacked_squares(20, -1.0f, 0.3f, 0.7f, 0.025f);
  // Room for 16 entries in all: 1 a tile, raised to the least room, 4.
  RendererOptions options{.small_triangle_max_area = 1, .initial_tile_entry_capacity = 16};
  const Frame direct = expect_same_image(scene, frame_of(64, 64), options, "20 squares");
  EXPECT_EQ(direct.stats.big_triangles, 40u);
  EXPECT_EQ(direct.stats.tile_entries, 40u);
  EXPECT_GE(direct.stats.tile_list_stride, 40u);
  EXPECT_EQ(direct.stats.attempts, 2u);  // the first overflowed a room of 4
}

TEST_F(TileLists, AutomaticListsTurnCountedWhenDirectOnesWouldTakeTooMuch) {
  // 512 x 512 px, tiles of 8: 4,096 tiles. At 103 px per unit at z = -1 (256 / (6 tan 22.5
  // deg)) and 98 at the farthest square (6.3 units away), squares from (0.015, -0.05) to
  // (0.05, -0.015) units cover pixels 257-262 across and down at most: tile (32, 32) alone.
  // 300 squares make one list of 600 entries and 600 entries in all. The room that list
  // needs for every tile is over 2 million entries, more than the 1 M (4 MiB) that automatic
  // lists allow when twice the entries is less.
  const Scene scene = stacked_squares(300, 0.015f, -0.05f, 0.035f, 0.001f);
  RendererOptions options{.small_triangle_max_area = 1, .tile_size = 8};
  const Frame direct = expect_same_image(scene, frame_of(512, 512), options, "300 squares");
  EXPECT_EQ(direct.stats.tile_entries, 600u);
  EXPECT_GE(direct.stats.tile_list_stride, 600u);  // direct lists on request, however long

  options.tile_lists = tessera::TileLists::automatic;
  Renderer renderer(context(), options);
  const Frame automatic = render(renderer, scene, frame_of(512, 512));
  EXPECT_EQ(automatic.stats.tile_list_stride, 0u);
  EXPECT_EQ(automatic.stats.attempts, 2u);  // the first, direct, overflowed its room
  EXPECT_EQ(automatic.stats.tile_entries, 600u);
  EXPECT_EQ(automatic.visibility, direct.visibility);
  // Counted for the rest of this scene; a new scene starts from direct lists again.
  EXPECT_EQ(render(renderer, scene, frame_of(512, 512)).stats.attempts, 1u);
  const Frame next =
      render(renderer, stacked_squares(2, 0.015f, -0.05f, 0.035f, 0.001f), frame_of(512, 512));
  EXPECT_GT(next.stats.tile_list_stride, 0u);
  EXPECT_EQ(next.stats.tile_entries, 4u);
}

// From a scene's second frame on, direct lists dispatch fill, raster_small and raster_tiles
// directly, sized by the frame before (renderer.cpp's dispatches_directly). Lists that outgrow
// those sizes take more turns of the passes' loops. Either way the image is a fresh renderer's.
TEST_F(TileLists, LaterFramesSizedByTheLastOneGiveTheSameImage) {
  // Boxes over 16 px binned, so that both lists have entries.
  const RendererOptions options{.small_triangle_max_area = 16,
                                .tile_lists = tessera::TileLists::direct};
  // Ten grid spheres of 960 triangles, the benchmark's family (core/bench_scenes.h).
  Scene near = make_bench_scene("grid", 10, 32, 4.0f / 3.0f);
  Scene far = near;
  far.camera.position = near.camera.target + 40.0f * (near.camera.position - near.camera.target);
  const FrameSettings settings = frame_of(320, 240);
  Renderer renderer(context(), options);
  const Frame first = render(renderer, far, settings);
  EXPECT_FALSE(first.stats.dispatched_directly) << "no frame before it to size the dispatches";
  const Frame again = render(renderer, far, settings);
  EXPECT_TRUE(again.stats.dispatched_directly);
  EXPECT_EQ(again.visibility, first.visibility);
  EXPECT_TRUE(same_bits(again.hdr, first.hdr));

  // The same triangles 40 times nearer: many more list entries than the far frame's sizes
  // launch a thread for (a quarter more and a workgroup: 256 small-triangle walks or 32 bin
  // entries), so the loops take several turns.
  const Frame grown = render(renderer, near, settings);
  EXPECT_TRUE(grown.stats.dispatched_directly);
  EXPECT_GT(grown.stats.small_triangles, 2 * again.stats.small_triangles + 2 * 256);
  EXPECT_GT(grown.stats.big_triangles, 2 * again.stats.big_triangles + 2 * 32);
  Renderer fresh(context(), options);
  const Frame reference = render(fresh, near, settings);
  EXPECT_FALSE(reference.stats.dispatched_directly);
  EXPECT_EQ(grown.visibility, reference.visibility);
  EXPECT_TRUE(same_bits(grown.hdr, reference.hdr));
  EXPECT_EQ(grown.ldr.pixels, reference.ldr.pixels);
}

}  // namespace
}  // namespace tessera
