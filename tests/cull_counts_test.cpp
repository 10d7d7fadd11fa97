// Setup's cull counts (FrameStats::culled_*), which each workgroup sums in shared memory before
// one atomic per kind (setup.comp), over thousands of workgroups and subgroups. A scene whose
// counts follow from its construction: planes facing the camera, planes facing away from it,
// and planes behind it.
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "compute/renderer.h"
#include "core/mesh.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class CullCounts : public test::VulkanTest {};

TEST_F(CullCounts, EveryTriangleIsCountedOnceWhereItsConstructionPutsIt) {
  constexpr int facing = 4000, away = 3000, behind = 2000;
  Scene s;
  s.camera.position = {0.0f, 0.0f, 10.0f};
  s.meshes.push_back(make_plane(1, 1));  // 2 triangles facing +z, towards the camera
  s.materials.push_back({});
  s.lights.push_back({});
  // Planes of 0.1 units, about 4 px wide at 320x240: their snapped areas are not zero, so
  // those facing away are culled by facing, not as empty.
  const glm::mat4 size = glm::scale(glm::mat4(1.0f), glm::vec3(0.05f));
  const glm::mat4 turned = glm::rotate(glm::mat4(1.0f), glm::pi<float>(), glm::vec3(0, 1, 0));
  for (int i = 0; i < facing + away + behind; ++i) {
    const glm::vec3 at(float(i % 60) * 0.12f - 3.6f, float((i / 60) % 50) * 0.1f - 2.5f,
                       i < facing + away ? 0.0f : 20.0f);  // behind the camera at z = 10
    const glm::mat4 m = glm::translate(glm::mat4(1.0f), at) * size;
    s.objects.push_back({0, 0, i >= facing && i < facing + away ? m * turned : m});
  }
  Renderer renderer(context());
  renderer.set_scene(s);
  const FrameStats stats = renderer.render(FrameSettings{.width = 320, .height = 240});
  EXPECT_EQ(stats.triangles_submitted, 2u * (facing + away + behind));
  EXPECT_EQ(stats.culled_backface, 2u * away);
  EXPECT_EQ(stats.culled_frustum, 2u * behind);
  EXPECT_EQ(stats.culled_nonfinite, 0u);
  EXPECT_EQ(stats.clipped, 0u);
  EXPECT_EQ(stats.raster_triangles + stats.culled_empty, 2u * facing);
  EXPECT_GT(stats.raster_triangles, 0u);
}

}  // namespace
}  // namespace tessera
