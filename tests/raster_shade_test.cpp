// Small frames rasterized and shaded in one pass (RendererOptions::raster_shade): from a small
// scene's second frame on, one workgroup per screen tile tests every raster triangle whose box
// meets its tile and shades its pixels, and every key and every bit of the image is the one the
// separate bin, rasterizer and shading passes give. The conditions under which a frame takes it
// are checked one by one.
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

class RasterShade : public test::VulkanTest {
 protected:
  // Renders `scene` twice with one renderer for each setting of raster_shade (the second frame
  // is the one that may take the single pass), expects the same visibility keys, HDR and
  // display images from both, and returns the second frame with it on.
  Frame expect_same_image(const Scene& scene, const FrameSettings& settings,
                          RendererOptions options, const std::string& what) {
    SCOPED_TRACE(what);
    options.shade_tiles = false;  // lavapipe's default, which the single pass does not go with
    options.raster_shade = false;
    Renderer off_renderer(context(), options);
    render(off_renderer, scene, settings);
    const Frame off = render(off_renderer, scene, settings);
    options.raster_shade = true;
    Renderer on_renderer(context(), options);
    const Frame first = render(on_renderer, scene, settings);
    // The first frame has no last frame's count to go by.
    EXPECT_FALSE(first.stats.rasterized_and_shaded);
    const Frame on = render(on_renderer, scene, settings);
    EXPECT_FALSE(off.stats.rasterized_and_shaded);
    EXPECT_EQ(on.stats.raster_triangles, off.stats.raster_triangles);
    // Setup counts the large triangles' box tiles alike in both kinds of frame (the next
    // frame's choice goes by them), which hold the tile lists' entries.
    EXPECT_EQ(on.stats.large_box_tiles, off.stats.large_box_tiles);
    EXPECT_GE(off.stats.large_box_tiles, off.stats.tile_entries);
    EXPECT_EQ(on.visibility, off.visibility);
    EXPECT_TRUE(same_bits(on.hdr, off.hdr));
    EXPECT_EQ(on.ldr.pixels, off.ldr.pixels);
    return on;
  }
};

// One grid sphere: 328 of its 960 triangles face the camera, more than a workgroup of 256 takes
// in one round, so the pass lists them in two; both rasterizers' triangles (boxes over 128 px
// are binned) and a size whose last tiles reach past the image.
TEST_F(RasterShade, OneSphereGivesTheSameKeysAndImage) {
  const Scene scene = make_bench_scene("grid", 1, 32, 100.0f / 75.0f);
  const Frame on = expect_same_image(scene, frame_of(100, 75), {}, "one grid sphere");
  EXPECT_TRUE(on.stats.rasterized_and_shaded);
  EXPECT_GT(on.stats.raster_triangles, 256u);
  EXPECT_LE(on.stats.raster_triangles, kRasterShadeMaxTriangles);
  EXPECT_GT(on.stats.pass_ms[size_t(Pass::raster_shade)], 0.0);
  EXPECT_EQ(on.stats.pass_ms[size_t(Pass::shade)], 0.0);
  EXPECT_EQ(on.stats.small_triangles, 0u);
  // At tiles of 8 px, and with depth rejection off (which the pass does not use either way).
  expect_same_image(scene, frame_of(100, 75), {.tile_size = 8}, "tiles of 8");
  expect_same_image(scene, frame_of(100, 75), {.depth_rejection = false}, "rejection off");
}

// Triangles whose keys compete: two large ones crossing each other in depth and a small one in
// front of both, drawn in both submission orders; the nearest key wins each pixel whichever
// rasterizer would have drawn it.
TEST_F(RasterShade, OverlappingTrianglesKeepTheNearestKey) {
  Mesh m;
  m.positions = {{-2.0f, -1.5f, -1.0f}, {2.0f, -1.5f, -3.0f}, {0.0f, 2.0f, -2.0f},
                 {-2.0f, 1.5f, -3.0f},  {2.0f, 1.5f, -1.0f},  {0.0f, -2.0f, -2.0f},
                 {0.1f, 0.1f, 0.0f},    {0.3f, 0.1f, 0.0f},   {0.1f, 0.3f, 0.0f}};
  m.normals.assign(m.positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  m.uvs.assign(m.positions.size(), glm::vec2(0.5f));
  m.indices = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  Scene scene;
  scene.meshes = {m};
  Material red, blue;
  red.base_color = {0.8f, 0.1f, 0.1f};
  blue.base_color = {0.1f, 0.2f, 0.9f};
  scene.materials = {red, blue};
  scene.objects = {{0, 0, glm::mat4(1.0f)},
                   {0, 1, glm::translate(glm::mat4(1.0f), {0.2f, 0.1f, -0.5f})}};
  Light light;
  light.position = {0.0f, 1.0f, 3.0f};
  light.intensity = 20.0f;
  scene.lights.push_back(light);
  scene.ambient = glm::vec3(0.1f);
  const Frame on = expect_same_image(scene, frame_of(64, 48), {}, "overlapping triangles");
  EXPECT_TRUE(on.stats.rasterized_and_shaded);
  std::swap(scene.objects[0], scene.objects[1]);
  expect_same_image(scene, frame_of(64, 48), {}, "the other order");
}

// What the shading reads besides the key: the environment behind and lighting the sphere
// (image-based lighting), a debug view, and a frame whose keys are not kept.
TEST_F(RasterShade, EnvironmentDebugViewAndUnkeptKeysGiveTheSameImage) {
  Scene scene = make_builtin_scene("environment");
  scene.objects.resize(1);
  FrameSettings settings = frame_of(80, 60);
  EXPECT_TRUE(expect_same_image(scene, settings, {}, "environment").stats.rasterized_and_shaded);
  settings.view = View::normal;
  expect_same_image(make_bench_scene("grid", 1, 32, 1.0f), settings, {}, "normal view");
  // Keys emptied by the frame that read them: the next one must find the buffer empty too.
  settings = frame_of(80, 60);
  settings.keep_visibility = false;
  const Scene sphere = make_bench_scene("grid", 1, 32, 80.0f / 60.0f);
  for (bool on : {false, true}) {
    SCOPED_TRACE(on ? "on" : "off");
    Renderer renderer(context(), {.shade_tiles = false, .raster_shade = on});
    Frame frames[3];
    for (Frame& f : frames) {
      renderer.set_scene(sphere);
      f.stats = renderer.render(settings);
      f.hdr = renderer.read_hdr();
      f.ldr = renderer.read_ldr();
    }
    EXPECT_EQ(frames[2].stats.rasterized_and_shaded, on);
    EXPECT_TRUE(same_bits(frames[1].hdr, frames[0].hdr));
    EXPECT_TRUE(same_bits(frames[2].hdr, frames[0].hdr));
    EXPECT_EQ(frames[2].ldr.pixels, frames[0].ldr.pixels);
  }
}

// Each condition of RendererOptions::raster_shade keeps a frame on the separate passes.
TEST_F(RasterShade, FramesOutsideItsConditionsTakeTheSeparatePasses) {
  const Scene one = make_bench_scene("grid", 1, 32, 1.0f);
  // The GPUs' settings (the suite runs on lavapipe, whose own choice is neither).
  auto second_frame = [&](const Scene& scene, RendererOptions options, FrameSettings settings) {
    if (!options.shade_tiles) options.shade_tiles = false;
    if (!options.raster_shade) options.raster_shade = true;
    Renderer renderer(context(), options);
    render(renderer, scene, settings);
    return render(renderer, scene, settings).stats;
  };
  EXPECT_TRUE(second_frame(one, {}, frame_of(64, 64)).rasterized_and_shaded);
  EXPECT_FALSE(second_frame(one, {.raster_shade = false}, frame_of(64, 64)).rasterized_and_shaded);
  EXPECT_FALSE(second_frame(one, {}, frame_of(64, 64, 4)).rasterized_and_shaded);
  EXPECT_FALSE(second_frame(one, {.debug_coverage = true}, frame_of(64, 64)).rasterized_and_shaded);
  EXPECT_FALSE(second_frame(one, {.shade_tiles = true}, frame_of(64, 64)).rasterized_and_shaded);
  EXPECT_FALSE(
      second_frame(one, {.specialize_lights = false}, frame_of(64, 64)).rasterized_and_shaded);
  EXPECT_FALSE(second_frame(one, {.max_batch_triangles = 500}, frame_of(64, 64))
                   .rasterized_and_shaded);  // two batches
  // Triangles covering the whole image: four meet each tile, as many as
  // kRasterShadeMaxTrianglesPerTile allows; five are more.
  const FrameStats four_huge =
      second_frame(make_bench_scene("huge", 4, 32, 1.0f), {}, frame_of(64, 64));
  EXPECT_TRUE(four_huge.rasterized_and_shaded);
  // Each box holds the whole image: 4 triangles in each of the 16 tiles of 16 px.
  EXPECT_EQ(four_huge.raster_triangles, 4u);
  EXPECT_EQ(four_huge.large_box_tiles, 64u);
  const FrameStats five = second_frame(make_bench_scene("huge", 5, 32, 1.0f), {}, frame_of(64, 64));
  EXPECT_EQ(five.large_box_tiles, 80u);
  EXPECT_FALSE(five.rasterized_and_shaded);
  // Four spheres set up more raster triangles than kRasterShadeMaxTriangles.
  const FrameStats four = second_frame(make_bench_scene("grid", 4, 32, 1.0f), {}, frame_of(64, 64));
  EXPECT_GT(four.raster_triangles, kRasterShadeMaxTriangles);
  EXPECT_FALSE(four.rasterized_and_shaded);
}

}  // namespace
}  // namespace tessera
