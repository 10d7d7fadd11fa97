// Setup's cull counts (FrameStats::culled_*), which each workgroup sums in shared memory before
// one atomic per kind (setup.comp), over thousands of workgroups and subgroups. A scene whose
// counts follow from its construction: planes facing the camera, planes facing away from it,
// and planes behind it; and the raster triangles the reference renderer counts, which must be the
// compute path's.
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "compute/renderer.h"
#include "core/builtin_scenes.h"
#include "core/mesh.h"
#include "core/reference_renderer.h"
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

// The reference counts the raster triangles setup keeps (ReferenceFrame::raster_triangles):
// after culling and clipping, less those whose box of at most 2 x 2 pixels covers no sample.
// At 1 x 1 pixels the default scene puts hundreds of triangles' boxes on the one pixel and one
// triangle on its centre; a floor crossing the near plane is clipped into pieces.
TEST_F(CullCounts, TheReferenceCountsTheRasterTrianglesTheComputePathKeeps) {
  Scene floor;
  floor.camera.position = {0.0f, 1.0f, 0.0f};
  floor.camera.target = {0.0f, 0.5f, -4.0f};
  floor.camera.near_plane = 0.5f;
  floor.meshes.push_back(make_plane(8, 8));  // in the xy plane, facing +z
  floor.materials.push_back({});
  floor.lights.push_back({});
  floor.objects.push_back({0, 0,
                           glm::rotate(glm::scale(glm::mat4(1.0f), glm::vec3(10.0f)),
                                       -glm::half_pi<float>(), glm::vec3(1, 0, 0))});
  struct Case {
    const char* name;
    Scene scene;
  };
  const Case cases[] = {{"default scene", make_builtin_scene("spheres")},
                        {"floor through the near plane", floor}};
  Renderer renderer(context());
  for (const Case& c : cases) {
    renderer.set_scene(c.scene);
    for (uint32_t side : {1u, 4u, 64u}) {
      for (uint32_t samples : {1u, 4u}) {
        const FrameSettings frame{.width = side, .height = side, .samples = samples};
        const FrameStats stats = renderer.render(frame);
        ReferenceSettings settings;
        settings.frame = frame;
        const ReferenceFrame reference = render_reference(c.scene, settings);
        EXPECT_EQ(reference.raster_triangles, stats.raster_triangles)
            << c.name << ", " << side << "x" << side << ", " << samples << " samples";
        if (side == 64 && c.scene.objects.size() == 1) {
          EXPECT_GT(stats.clipped, 0u) << c.name;
        }
      }
    }
  }
}

}  // namespace
}  // namespace tessera
