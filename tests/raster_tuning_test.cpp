// Device-tuned rasterization (raster_tuning, compute/renderer.h): GPUs keep RendererOptions'
// defaults and shade every pixel, CPU devices take more triangles on the per-triangle
// rasterizer and shade by tiles, and either choice leaves every bit of the visibility buffer
// and the image as it is.
#include <cstring>
#include <iterator>

#include <gtest/gtest.h>

#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "host/bench_measure.h"
#include "host/cli.h"
#include "host/tradeoff.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

TEST(RasterTuning, GpusKeepTheRendererDefaults) {
  const RendererOptions defaults;
  for (VkPhysicalDeviceType type :
       {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU,
        VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU, VK_PHYSICAL_DEVICE_TYPE_OTHER}) {
    const RasterTuning t = raster_tuning(type);
    EXPECT_EQ(t.small_triangle_max_area, defaults.small_triangle_max_area) << type;
    EXPECT_EQ(t.depth_rejection, defaults.depth_rejection) << type;
    // Measured slower on the H200 (docs/performance.md, "Shading by tiles").
    EXPECT_FALSE(t.shade_tiles) << type;
    EXPECT_EQ(t.tile_lists, defaults.tile_lists) << type;
    // Measured faster on the H200 (docs/performance.md, "Issue 13, thirteenth round").
    EXPECT_TRUE(t.raster_shade) << type;
  }
}

// docs/performance.md, "Device-tuned rasterization": 4096 px, rejection as on GPUs.
TEST(RasterTuning, CpuDevicesRasterizeBoxesUpTo4096PixelsPerTriangle) {
  const RasterTuning t = raster_tuning(VK_PHYSICAL_DEVICE_TYPE_CPU);
  EXPECT_EQ(t.small_triangle_max_area, 4096u);
  EXPECT_TRUE(t.depth_rejection);
  EXPECT_TRUE(t.shade_tiles);
  EXPECT_EQ(t.tile_lists, TileLists::counted);
  // One workgroup per tile runs the whole shading code for all its pixels there, and shading by
  // tiles, which saves that for the background, cannot go with it.
  EXPECT_FALSE(t.raster_shade);
}

class RasterTuningOnDevice : public test::VulkanTest {};

// The suite runs on lavapipe, a CPU device: the tool's renderers take the CPU tuning, and
// keep every other option they are given.
TEST_F(RasterTuningOnDevice, LavapipeTakesTheCpuTuningAndKeepsTheOtherOptions) {
  ASSERT_EQ(context().properties.deviceType, VK_PHYSICAL_DEVICE_TYPE_CPU);
  const RendererOptions tuned = tuned_for_device(context(), {.tile_size = 8, .resolve = false});
  const RasterTuning cpu = raster_tuning(VK_PHYSICAL_DEVICE_TYPE_CPU);
  EXPECT_EQ(tuned.small_triangle_max_area, cpu.small_triangle_max_area);
  EXPECT_EQ(tuned.depth_rejection, cpu.depth_rejection);
  EXPECT_EQ(tuned.shade_tiles, cpu.shade_tiles);
  EXPECT_EQ(tuned.tile_lists, cpu.tile_lists);
  EXPECT_EQ(tuned.raster_shade, cpu.raster_shade);
  EXPECT_EQ(tuned.tile_size, 8u);
  EXPECT_FALSE(tuned.resolve);
}

// `tessera bench` renders as `render` does on the device: a CPU device walks every box whole
// (raster_tuning), whatever area the command line gives; the options it has are its own.
TEST_F(RasterTuningOnDevice, BenchWalksBoxesAsTheDeviceDoes) {
  ASSERT_EQ(context().properties.deviceType, VK_PHYSICAL_DEVICE_TYPE_CPU);
  const RasterTuning cpu = raster_tuning(VK_PHYSICAL_DEVICE_TYPE_CPU);
  BenchArgs args =
      parse_command_line({"bench", "--small-triangle-area", "256", "--tile-size", "8"}).bench;
  const RendererOptions options = bench_renderer_options(context(), args);
  EXPECT_EQ(options.small_triangle_walk_area, cpu.small_triangle_walk_area);
  EXPECT_EQ(options.small_triangle_max_area, 256u);
  EXPECT_EQ(options.tile_size, 8u);
}

// A --quality preset's small-triangle area is the GPUs' setting: `tradeoff` on a CPU device
// keeps the device's own (docs/tradeoffs.md, "Presets"), and takes the rest of the preset.
TEST_F(RasterTuningOnDevice, QualityPresetsKeepACpuDevicesSmallTriangleArea) {
  ASSERT_EQ(context().properties.deviceType, VK_PHYSICAL_DEVICE_TYPE_CPU);
  EXPECT_FALSE(preset_sets_small_triangle_area(VK_PHYSICAL_DEVICE_TYPE_CPU));
  for (VkPhysicalDeviceType gpu :
       {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU,
        VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU, VK_PHYSICAL_DEVICE_TYPE_OTHER})
    EXPECT_TRUE(preset_sets_small_triangle_area(gpu)) << gpu;
  const RasterTuning cpu = raster_tuning(VK_PHYSICAL_DEVICE_TYPE_CPU);
  for (const char* quality : {"draft", "balanced", "reference"}) {
    const TradeoffArgs args =
        parse_command_line({"tradeoff", "--quality", quality, "--knob", "small-triangle"}).tradeoff;
    const RendererOptions options = tradeoff_base_options(context(), args);
    EXPECT_EQ(options.small_triangle_max_area, cpu.small_triangle_max_area) << quality;
    EXPECT_EQ(options.small_triangle_walk_area, cpu.small_triangle_walk_area) << quality;
    EXPECT_EQ(options.environment.specular_size, args.env_options.specular_size) << quality;
    EXPECT_EQ(options.tile_size, args.tile_size) << quality;
  }
}

// Left unset, shading by tiles is the device's choice: on for lavapipe, whose frames then
// count every tile as shaded or background.
TEST_F(RasterTuningOnDevice, LavapipeShadesByTilesUnlessTold) {
  const Scene scene = make_bench_scene("grid", 1, 32, 1.0f);
  const Frame automatic = render(scene, 64, 48, RendererOptions{});
  EXPECT_EQ(automatic.stats.shaded_tiles + automatic.stats.background_tiles, 4u * 3u);
  EXPECT_GT(automatic.stats.shaded_tiles, 0u);
  const Frame off = render(scene, 64, 48, RendererOptions{.shade_tiles = false});
  EXPECT_EQ(off.stats.shaded_tiles + off.stats.background_tiles, 0u);
}

bool same_bits(const void* a, const void* b, size_t bytes) {
  return std::memcmp(a, b, bytes) == 0;
}

// One sphere filling a 160 x 160 image (grid family, N = 1), whose triangles the GPU tuning bins
// into tiles and the CPU tuning rasterizes one thread each; two triangles each many times the
// screen (huge family), binned by both; and the default scene. The keys and the image are the
// same bits.
TEST_F(RasterTuningOnDevice, EveryTuningGivesTheSameBits) {
  const Scene scenes[] = {make_bench_scene("grid", 1, 32, 1.0f),
                          make_bench_scene("huge", 2, 32, 1.0f), make_builtin_scene("spheres")};
  for (size_t i = 0; i < std::size(scenes); ++i) {
    const Scene& scene = scenes[i];
    RendererOptions gpu, cpu;
    const RasterTuning g = raster_tuning(VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU);
    const RasterTuning c = raster_tuning(VK_PHYSICAL_DEVICE_TYPE_CPU);
    gpu.small_triangle_max_area = g.small_triangle_max_area;
    gpu.depth_rejection = g.depth_rejection;
    gpu.shade_tiles = g.shade_tiles;
    gpu.tile_lists = g.tile_lists;
    cpu.small_triangle_max_area = c.small_triangle_max_area;
    cpu.depth_rejection = c.depth_rejection;
    cpu.shade_tiles = c.shade_tiles;
    cpu.tile_lists = c.tile_lists;
    const Frame a = render(scene, 160, 160, gpu);
    const Frame b = render(scene, 160, 160, cpu);
    // Not vacuous: the sphere's triangles took different rasterizers, the huge ones the tiles.
    if (i == 0) {
      EXPECT_GT(b.stats.small_triangles, a.stats.small_triangles);
    } else if (i == 1) {
      EXPECT_GT(b.stats.big_triangles, 0u);
    }
    ASSERT_EQ(a.visibility.size(), b.visibility.size());
    EXPECT_TRUE(same_bits(a.visibility.data(), b.visibility.data(),
                          a.visibility.size() * sizeof(uint64_t)));
    ASSERT_EQ(a.hdr.pixels.size(), b.hdr.pixels.size());
    EXPECT_TRUE(same_bits(a.hdr.pixels.data(), b.hdr.pixels.data(),
                          a.hdr.pixels.size() * sizeof(glm::vec4)));
    ASSERT_EQ(a.ldr.pixels.size(), b.ldr.pixels.size());
    EXPECT_TRUE(same_bits(a.ldr.pixels.data(), b.ldr.pixels.data(),
                          a.ldr.pixels.size() * sizeof(glm::u8vec4)));
  }
}

}  // namespace
}  // namespace tessera
