// Shading by tiles (RendererOptions::shade_tiles): the shading code runs only in the screen
// tiles the rasterizers drew into, the background apart, and every bit of the image is the
// one shading every pixel gives, whatever the tile size, sample count, anti-aliasing weights,
// view, batching, environment or image size. The tile counts are checked against scenes whose
// covered tiles are known by hand.
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

class ShadeTiles : public test::VulkanTest {
 protected:
  // Renders `scene` with shading by tiles off and on (the same options otherwise) and expects
  // the same visibility buffer, HDR and display images; returns the frame with it on.
  Frame expect_same_image(const Scene& scene, FrameSettings settings, RendererOptions options,
                          const std::string& what) {
    SCOPED_TRACE(what);
    options.shade_tiles = false;
    Renderer off_renderer(context(), options);
    const Frame off = render(off_renderer, scene, settings);
    options.shade_tiles = true;
    Renderer on_renderer(context(), options);
    const Frame on = render(on_renderer, scene, settings);
    EXPECT_EQ(off.stats.shaded_tiles + off.stats.background_tiles, 0u);
    const uint64_t tiles_x = (settings.width + options.tile_size - 1) / options.tile_size;
    const uint64_t tiles_y = (settings.height + options.tile_size - 1) / options.tile_size;
    EXPECT_EQ(on.stats.shaded_tiles + on.stats.background_tiles, tiles_x * tiles_y);
    EXPECT_EQ(on.visibility, off.visibility);
    EXPECT_TRUE(same_bits(on.hdr, off.hdr));
    EXPECT_EQ(on.ldr.pixels, off.ldr.pixels);
    return on;
  }
};

// A right triangle of legs `leg` at the origin, facing +z.
Mesh triangle(float leg) {
  Mesh m;
  m.positions = {{0.0f, 0.0f, 0.0f}, {leg, 0.0f, 0.0f}, {0.0f, leg, 0.0f}};
  m.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
  m.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
  m.indices = {0, 1, 2};
  return m;
}

TEST_F(ShadeTiles, SameBitsOnBothRasterizersAtAnOddSize) {
  // Both rasterizers (boxes over 64 px are binned into tiles), and a size at which the last row
  // and column of tiles reach past the image. The suite's golden images, rendered with shading
  // by tiles (lavapipe's default), check the other built-in scenes and settings.
  for (const char* name : {"spheres", "textured"}) {
    expect_same_image(make_builtin_scene(name), frame_of(100, 75), {}, name);
  }
}

TEST_F(ShadeTiles, SameBitsAtEveryTileSizeSampleCountAndWeighting) {
  const Scene scene = make_builtin_scene("spheres");
  struct Case {
    uint32_t tile, samples;
    AaCoverage aa;
  };
  for (Case c : {Case{8, 1, AaCoverage::count}, Case{8, 4, AaCoverage::count},
                 Case{8, 4, AaCoverage::analytic}, Case{8, 4, AaCoverage::silhouette},
                 Case{16, 4, AaCoverage::silhouette}}) {
    FrameSettings settings = frame_of(96, 80, c.samples);
    settings.aa_coverage = c.aa;
    const Frame on =
        expect_same_image(scene, settings, {.tile_size = c.tile},
                          "tile " + std::to_string(c.tile) + ", " + std::to_string(c.samples) +
                              " samples, " + aa_coverage_name(c.aa));
    EXPECT_GT(on.stats.shaded_tiles, 0u);
    // Tiles of 8 px fit between the spheres; every tile of 16 px holds some sphere.
    if (c.tile == 8) {
      EXPECT_GT(on.stats.background_tiles, 0u);
    }
  }
}

TEST_F(ShadeTiles, SameBitsInADebugViewInBatchesAndWithTheEnvironmentBehind) {
  FrameSettings normals = frame_of(64, 64);
  normals.view = View::normal;
  expect_same_image(make_builtin_scene("spheres"), normals, {}, "normal view");
  // Batches of 2,000 triangle instances: the tiles later batches draw into are marked too.
  expect_same_image(make_builtin_scene("spheres"), frame_of(64, 64), {.max_batch_triangles = 2000},
                    "batches");
  // The environment seen along each background pixel's ray, at 4 samples, with the CPU
  // devices' small-triangle threshold (every triangle per thread).
  expect_same_image(make_builtin_scene("environment"), frame_of(80, 48, 4),
                    {.small_triangle_max_area = kCpuSmallTriangleArea}, "environment");
}

TEST_F(ShadeTiles, OnlyTilesWithSomethingDrawnAreShaded) {
  // 64 x 64 px, tiles of 16: 16 tiles. The default camera (z = 5, 45 degree field of view)
  // sees 12.9 px per unit at z = -1 (6 units away), 64 / 2 / (6 tan 22.5 deg) px per unit, with
  // the origin at the image's centre, pixel 32.
  Scene scene;
  scene.meshes = {triangle(0.5f)};
  scene.materials = {Material{}};
  // Nothing drawn: every tile is background.
  Renderer renderer(context(), {.shade_tiles = true});
  Frame empty = render(renderer, scene, 64, 64);
  EXPECT_EQ(empty.stats.shaded_tiles, 0u);
  EXPECT_EQ(empty.stats.background_tiles, 16u);
  // A triangle of about 6.5 x 6.5 px with its right angle at (0.3, 0.3) units, pixel
  // (32 + 3.9, 32 - 3.9) = (35.9, 28.1), reaching up and right to about (42.3, 21.7): inside
  // tile (2, 1) (pixels 32-47 across, 16-31 down) alone, so one tile is shaded.
  scene.objects.push_back({0, 0, glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.3f, -1.0f))});
  Frame one = render(renderer, scene, 64, 64);
  EXPECT_EQ(one.stats.shaded_tiles, 1u);
  EXPECT_EQ(one.stats.background_tiles, 15u);
  // Moved to straddle the centre, pixel (32, 32), where four tiles meet: those four.
  scene.objects[0].transform = glm::translate(glm::mat4(1.0f), glm::vec3(-0.2f, -0.2f, -1.0f));
  Frame four = render(renderer, scene, 64, 64);
  EXPECT_EQ(four.stats.shaded_tiles, 4u);
  EXPECT_EQ(four.stats.background_tiles, 12u);
  // Every pixel outside the triangle's box shows the background in both frames.
  Renderer off(context(), {});
  EXPECT_EQ(render(off, scene, 64, 64).ldr.pixels, four.ldr.pixels);
}

}  // namespace
}  // namespace tessera
