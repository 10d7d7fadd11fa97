// The compute path against the independent reference renderer: built-in scenes, random scenes
// from a fixed seed list, every stability case, and odd image sizes. Bars: docs/accuracy.md.
#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "tests/accuracy_support.h"
#include "tests/test_scenes.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class Accuracy : public test::VulkanTest {};

TEST_F(Accuracy, BuiltinScenes) {
  for (const auto& info : builtin_scenes()) {
    const Scene scene = make_builtin_scene(info.name);
    // With an environment only ownership and finiteness are held to bars (below): ownership is
    // the reference's rasterization and finiteness the compute path's image, neither of which
    // depends on the reference's shading. So its Monte Carlo integral takes 1 direction per
    // pixel instead of 1024, which was most of this test's time (the printed HDR and 8-bit
    // errors of that scene then measure against a noisy reference).
    const uint32_t environment_samples = scene.environment ? 1 : 1024;
    test::AccuracyReport r =
        test::compare_with_reference(context(), scene, 512, 512, std::string(info.name), {},
                                     Brdf::classic, 1, environment_samples);
    if (scene.environment) {
      // The split-sum is an approximation of the reference's Monte Carlo integral, with its
      // own bars (ibl_test.cpp); here only what the rasterizer decides is held to these.
      EXPECT_EQ(r.unexplained, 0u) << info.name;
      EXPECT_TRUE(r.finite) << info.name;
      continue;
    }
    test::expect_meets_bars(r);
  }
}

class AccuracyRandom : public test::VulkanTest, public ::testing::WithParamInterface<uint32_t> {};

TEST_P(AccuracyRandom, RandomScene) {
  const uint32_t seed = GetParam();
  test::AccuracyReport r = test::compare_with_reference(context(), test::random_scene(seed), 200,
                                                        150, "random_" + std::to_string(seed));
  test::expect_meets_bars(r);
}

INSTANTIATE_TEST_SUITE_P(Seeds, AccuracyRandom,
                         ::testing::Values(1u, 2u, 3u, 5u, 8u, 13u, 21u, 34u));

class Stability : public test::VulkanTest,
                  public ::testing::WithParamInterface<test::StabilityCase> {};

TEST_P(Stability, AgreesWithReference) {
  const test::StabilityCase& c = GetParam();
  RendererOptions options;
  options.cull = c.cull;
  test::AccuracyReport r =
      test::compare_with_reference(context(), c.make(), c.width, c.height, c.name, options);
  test::expect_meets_bars(r);
  EXPECT_GT(r.covered, 0u) << "every case draws something";
}

INSTANTIATE_TEST_SUITE_P(Cases, Stability, ::testing::ValuesIn(test::stability_cases()),
                         [](const ::testing::TestParamInfo<test::StabilityCase>& info) {
                           return info.param.name;
                         });

struct Size {
  uint32_t width, height;
};
void PrintTo(const Size& s, std::ostream* os) {
  *os << s.width << "x" << s.height;
}

class AccuracySizes : public test::VulkanTest, public ::testing::WithParamInterface<Size> {};

TEST_P(AccuracySizes, DefaultScene) {
  const Size size = GetParam();
  test::AccuracyReport r = test::compare_with_reference(
      context(), make_sphere_grid_scene(), size.width, size.height,
      "spheres_" + std::to_string(size.width) + "x" + std::to_string(size.height));
  test::expect_meets_bars(r);
}

// 4096x4096 is the largest image whose visibility buffer fits lavapipe's 128 MiB storage range.
INSTANTIATE_TEST_SUITE_P(Sizes, AccuracySizes,
                         ::testing::Values(Size{1, 1}, Size{2, 3}, Size{333, 77}, Size{77, 333},
                                           Size{4096, 4096}),
                         [](const ::testing::TestParamInfo<Size>& info) {
                           return std::to_string(info.param.width) + "x" +
                                  std::to_string(info.param.height);
                         });

}  // namespace
}  // namespace tessera
