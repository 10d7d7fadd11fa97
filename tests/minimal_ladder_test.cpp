// The minimal graphics program's ladder (bench/minimal_graphics.cpp --variant): every rung
// draws the hardware baseline's picture of the yardstick scene, the rungs that keep the minimal
// program's shading to within fp16 rounding and the last one, which runs the baseline's own
// shaders on the baseline's data, exactly. Not a timing test: the ladder's figures are measured
// on the device (scripts/device-bench-yardstick.sh, docs/performance.md).
#include <string>

#include <gtest/gtest.h>

#include "compute/baselines/hardware_baseline.h"
#include "core/bench_scenes.h"
#include "core/image.h"
#include "core/image_metrics.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class MinimalLadder : public test::VulkanTest {};

TEST_F(MinimalLadder, EveryRungDrawsTheBaselinesPicture) {
#ifndef TESSERA_MINIMAL_GRAPHICS
  GTEST_SKIP() << "built without bench/ (TESSERA_BUILD_BENCH off)";
#else
  const uint32_t w = 96, h = 54, n = 10;
  const std::string prefix = test::output_path("ladder");
  std::string out;
  // The validation layer prints to stdout when no messenger is installed.
  // Appended piece by piece: GCC 12 warns (-Warray-bounds, wrongly) about a chain of + on
  // string literals.
  std::string command = "VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation ";
  command.append(TESSERA_MINIMAL_GRAPHICS);
  command.append(" --device lavapipe --objects 10 --size 96x54 --repeat 1 ");
  command.append("--warmup 0 --warmup-ms 0 --variant all --pfm ");
  command.append(prefix);
  ASSERT_EQ(test::run_command(command, out), 0) << out;
  EXPECT_EQ(out.find("Validation"), std::string::npos) << out;

  Renderer renderer(context());
  renderer.set_scene(make_bench_scene("yardstick", n, 32, float(w) / float(h)));
  FrameSettings fs;
  fs.width = w;
  fs.height = h;
  HardwareBaseline(renderer).render(fs);
  const ImageF baseline = renderer.read_hdr();

  const char* const rungs[] = {"",
                               "reverse_depth_",
                               "transfer_layout_",
                               "storage_shading_",
                               "vertex_pulling_",
                               "baseline_vertex_",
                               "tessera_brdf_",
                               "baseline_shaders_"};
  for (const char* rung : rungs) {
    const ImageF image = read_pfm(prefix + "_" + rung + std::to_string(n) + ".pfm");
    ASSERT_EQ(image.width, w);
    ASSERT_EQ(image.height, h);
    // Both clear to the scene's background, stored as fp16: the top row is empty at N = 10
    // (the 4 x 4 grid's top row holds no sphere).
    const glm::vec3 clear_minimal(image.pixels[0]), clear_baseline(baseline.pixels[0]);
    std::vector<uint8_t> covered(image.pixels.size(), 0);
    size_t coverage_differs = 0, covered_count = 0;
    for (size_t i = 0; i < covered.size(); ++i) {
      const bool a = glm::vec3(image.pixels[i]) != clear_minimal,
                 b = glm::vec3(baseline.pixels[i]) != clear_baseline;
      coverage_differs += a != b;
      covered[i] = a && b;
      covered_count += a && b;
    }
    EXPECT_EQ(coverage_differs, 0u) << rung;
    EXPECT_GT(covered_count, 1000u) << rung;
    const ImageDifference d = compare_images(image, baseline, 0.0, &covered, 1e-3);
    if (std::string(rung) == "baseline_shaders_") {
      // The baseline's shaders, specialization, data and depth: its picture to the bit.
      EXPECT_EQ(d.max_abs_error, 0.0) << rung;
    } else {
      // The same radiance up to float rounding, each stored as fp16 (11 significant bits):
      // at most one fp16 step apart, 2^-10 of the value.
      EXPECT_LE(d.max_relative_error, 1.0 / 1024.0)
          << rung << " at " << d.worst_x << ", " << d.worst_y;
    }
  }
#endif
}

// --variant names rungs by number or name; anything else is refused before a device is made.
TEST(MinimalLadderCli, UnknownOrRepeatedRungsAreClearErrors) {
#ifndef TESSERA_MINIMAL_GRAPHICS
  GTEST_SKIP() << "built without bench/ (TESSERA_BUILD_BENCH off)";
#else
  const std::string program = TESSERA_MINIMAL_GRAPHICS;
  std::string out;
  EXPECT_EQ(test::run_command(program + " --variant 8", out), 1) << out;
  EXPECT_NE(out.find("--variant: expects all, or rungs 0 to 7"), std::string::npos) << out;
  EXPECT_NE(out.find("got '8'"), std::string::npos) << out;
  EXPECT_EQ(test::run_command(program + " --variant minimal,reverse_depth,0", out), 1) << out;
  EXPECT_NE(out.find("--variant: rung '0' given twice"), std::string::npos) << out;
  EXPECT_EQ(test::run_command(program + " --variant 1,,2", out), 1) << out;
  EXPECT_NE(out.find("got ''"), std::string::npos) << out;
#endif
}

}  // namespace
}  // namespace tessera
