// An image test written with Tessera::test_support: the default scene rendered on lavapipe
// against Tessera's CPU reference renderer (double precision, its own shading code).
#include <gtest/gtest.h>

#include "compute/renderer.h"
#include "core/builtin_scenes.h"
#include "core/reference_renderer.h"
#include "tests/support/image_assertions.h"

TEST(RenderSpheres, MatchesTheReferenceRenderer) {
  const tessera::Scene scene = tessera::make_sphere_grid_scene();
  const tessera::FrameSettings frame{.width = 128, .height = 128};
  auto ctx = tessera::create_context({.device = "lavapipe"});
  tessera::Renderer renderer(*ctx);
  renderer.set_scene(scene);
  renderer.render(frame);
  const tessera::Image8 gpu = renderer.read_ldr();

  const tessera::ReferenceFrame reference = tessera::render_reference(scene, {.frame = frame});
  // docs/accuracy.md: at most 3 levels, and only on ill-conditioned silhouette pixels.
  EXPECT_IMAGES_NEAR(gpu, reference.ldr, 3);
}
