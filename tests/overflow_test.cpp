// Buffers that are too small grow and the frame is rendered again; batches split the work.
// Either way the image is the one a roomy renderer makes: nothing is dropped.
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/mesh.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class Overflow : public test::VulkanTest {};

Scene mixed_sizes_scene() {
  Scene s = make_sphere_grid_scene();
  s.camera.position = {0.0f, 0.0f, 8.0f};
  // Cubes whose triangles are binned into many tiles each.
  s.meshes.push_back(make_cube());
  for (int i = 0; i < 4; ++i) {
    glm::mat4 t =
        glm::translate(glm::mat4(1.0f), glm::vec3(-2.5f + 1.7f * i, 1.0f - 0.6f * i, 1.0f));
    s.objects.push_back(
        {1, uint32_t(i), glm::rotate(t, 0.5f * i + 0.3f, glm::vec3(0.3f, 1.0f, 0.2f))});
  }
  return s;
}

TEST_F(Overflow, TinyStartingCapacitiesGrowAndMatch) {
  Scene scene = mixed_sizes_scene();
  Frame roomy = render(scene, 160, 160);
  EXPECT_EQ(roomy.stats.attempts, 1u);
  RendererOptions tiny;
  tiny.initial_raster_capacity = 16;
  tiny.initial_tile_entry_capacity = 16;
  Frame grown = render(scene, 160, 160, tiny);
  EXPECT_GT(grown.stats.attempts, 1u);
  EXPECT_GT(grown.stats.big_triangles, 0u);
  EXPECT_EQ(roomy.visibility, grown.visibility);
  EXPECT_EQ(roomy.ldr.pixels, grown.ldr.pixels);
}

TEST_F(Overflow, BatchesAndHardLimitsSplitTheWork) {
  Scene scene = mixed_sizes_scene();
  Frame roomy = render(scene, 160, 160);
  RendererOptions split;
  split.max_batch_triangles = 5000;
  // Scratch buffers capped at 64 KiB: 1365 raster triangles, 16k tile entries. Growing stops
  // there, so the renderer must halve its batches until each fits.
  split.max_scratch_buffer_bytes = 64 << 10;
  Frame batched = render(scene, 160, 160, split);
  EXPECT_GT(batched.stats.batches, scene.objects.size() * 4032 / 5000);
  EXPECT_EQ(roomy.stats.raster_triangles, batched.stats.raster_triangles);
  EXPECT_EQ(roomy.visibility, batched.visibility);
  EXPECT_EQ(roomy.ldr.pixels, batched.ldr.pixels);
}

}  // namespace
}  // namespace tessera
