// The graphics-pipeline baseline renders the same image as the compute path (so benchmarks
// compare the same work), within the bars of docs/performance.md.
#include <gtest/gtest.h>

#include "compute/baselines/hardware_baseline.h"
#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "core/image_metrics.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class HardwareBaseline : public test::VulkanTest {};

struct Compared {
  ImageDifference ldr;
  size_t pixels_differing_in_coverage = 0;
};

Compared compare_paths(Context& ctx, const Scene& scene, uint32_t w, uint32_t h,
                       Brdf brdf = Brdf::classic, Lod lod = Lod::off) {
  Renderer renderer(ctx);
  renderer.set_scene(scene);
  FrameSettings fs;
  fs.width = w;
  fs.height = h;
  fs.brdf = brdf;
  fs.lod = lod;
  const FrameStats compute_stats = renderer.render(fs);
  const Image8 compute = renderer.read_ldr();
  const ImageF compute_hdr = renderer.read_hdr();
  // Qualified: this file's test fixture has the same name.
  ::tessera::HardwareBaseline baseline(renderer);
  BaselineStats stats = baseline.render(fs);
  EXPECT_GE(stats.draws, 1u);
  const Image8 hardware = renderer.read_ldr();
  // Under level of detail both paths drew the levels the lod passes chose: the same triangles.
  if (lod == Lod::automatic) {
    EXPECT_LT(compute_stats.triangles_submitted, compute_stats.triangles_without_lod);
  }
  const ImageF hardware_hdr = renderer.read_hdr();
  Compared c;
  // Pixels that one path covers and the other does not (background exactly on one side only).
  std::vector<uint8_t> both(compute.pixels.size(), 1);
  const glm::vec3 bg = glm::vec3(compute_hdr.pixels[0]);  // corner pixels are background here
  for (size_t i = 0; i < both.size(); ++i) {
    const bool a = glm::vec3(compute_hdr.pixels[i]) == bg,
               b = glm::vec3(hardware_hdr.pixels[i]) == bg;
    if (a != b) {
      both[i] = 0;
      c.pixels_differing_in_coverage++;
    }
  }
  c.ldr = compare_images(hardware, compute, 1.0, &both);
  std::printf(
      "BASELINE %ux%u: %zu px differ in coverage, 8-bit max %.0f, %zu px over 1 level, PSNR %.1f "
      "dB\n",
      w, h, c.pixels_differing_in_coverage, c.ldr.max_abs_error, c.ldr.pixels_over, c.ldr.psnr_db);
  if (c.ldr.max_abs_error > 2) {
    write_png(testing::test_output_path("compute.png"), compute);
    write_png(testing::test_output_path("hardware.png"), hardware);
    write_png(testing::test_output_path("difference.png"),
              difference_image(hardware, compute, 4.0, &both));
  }
  return c;
}

TEST_F(HardwareBaseline, DefaultSceneMatchesTheComputePath) {
  Compared c = compare_paths(context(), make_sphere_grid_scene(), 512, 512);
  EXPECT_LE(c.pixels_differing_in_coverage, 10u);
  // Measured: 0 pixels differ in coverage, 8-bit values within 1 level (PSNR 81 dB).
  EXPECT_LE(c.ldr.max_abs_error, 2.0);
  EXPECT_LE(c.ldr.fraction_over, 1e-4);
}

TEST_F(HardwareBaseline, LevelsOfDetailMatchTheComputePath) {
  for (const Scene& scene : {make_sphere_grid_scene(), make_bench_scene("grid", 300, 32, 1.0f)}) {
    Compared c = compare_paths(context(), scene, 256, 256, Brdf::classic, Lod::automatic);
    EXPECT_LE(c.pixels_differing_in_coverage, 10u);
    EXPECT_LE(c.ldr.max_abs_error, 2.0);
  }
}

TEST_F(HardwareBaseline, BenchmarkFamiliesMatchTheComputePath) {
  for (const auto& family : bench_families()) {
    Compared c =
        compare_paths(context(), make_bench_scene(family.name, 30, 16, 4.0f / 3.0f), 200, 150);
    EXPECT_LE(c.pixels_differing_in_coverage, 10u) << family.name;
    EXPECT_LE(c.ldr.max_abs_error, 2.0) << family.name;
  }
}

TEST_F(HardwareBaseline, EveryLightTypeAndBrdfVariantMatchesTheComputePath) {
  for (Brdf brdf : {Brdf::classic, Brdf::filament, Brdf::blinn_phong}) {
    Compared c = compare_paths(context(), make_lights_scene(), 320, 200, brdf);
    EXPECT_LE(c.pixels_differing_in_coverage, 10u);
    EXPECT_LE(c.ldr.max_abs_error, 2.0);
  }
}

}  // namespace
}  // namespace tessera
