// Predicting that a frame has nothing to clip (core/clip_prediction.h): boxes inside the near
// plane and the guard band by more than the rounding margin need no clipping, boxes reaching
// past either may; the renderer leaves the clip pass out of frames predicted to have nothing to
// clip and keeps it, with the clipped triangles, in the others. Expected values come from the
// default camera's geometry, worked by hand below.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/clip_prediction.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

// The default camera (at z = 5 looking down -z, near plane 0.1) at aspect 1: clip w is
// 5 - z, and clip x is x * cot(22.5 deg) = 2.414 x.
glm::dmat4 default_clip_from_world() {
  const Camera camera;
  return glm::dmat4(projection_matrix(camera, 1.0f)) * glm::dmat4(view_matrix(camera));
}

// The guard band of a 64 x 64 image: +-32,768 px is 1,023 in NDC units (2 * 32768 / 64 - 1).
const glm::dvec2 kBand(1023.0, 1023.0);

const MeshBox kUnitCube{glm::vec3(-0.5f), glm::vec3(0.5f)};

bool needs_clipping_at(const MeshBox& box, glm::vec3 at) {
  return may_need_clipping(box, default_clip_from_world(),
                           glm::dmat4(glm::translate(glm::mat4(1.0f), at)), 0.1, kBand);
}

TEST(ClipPrediction, MeshBoxBoundsEveryPosition) {
  Mesh mesh;
  mesh.positions = {{1.0f, -2.0f, 3.0f}, {-4.0f, 5.0f, 0.5f}, {0.0f, 0.0f, -6.0f}};
  const MeshBox box = mesh_box(mesh);
  EXPECT_EQ(box.min, glm::vec3(-4.0f, -2.0f, -6.0f));
  EXPECT_EQ(box.max, glm::vec3(1.0f, 5.0f, 3.0f));
  // An empty mesh has an empty box, which needs no clipping wherever it is.
  const MeshBox empty = mesh_box(Mesh{});
  EXPECT_GT(empty.min.x, empty.max.x);
  EXPECT_FALSE(needs_clipping_at(empty, glm::vec3(0.0f, 0.0f, 5.0f)));
}

TEST(ClipPrediction, ABoxInFrontAndInsideTheBandNeedsNone) {
  // At the origin: w from 4.5 to 5.5, |x| / w at most 2.414 * 0.5 / 4.5 = 0.27.
  EXPECT_FALSE(needs_clipping_at(kUnitCube, glm::vec3(0.0f)));
  // Its near face at z = 4.4: w = 0.6, 0.5 in front of the near plane.
  EXPECT_FALSE(needs_clipping_at(kUnitCube, glm::vec3(0.0f, 0.0f, 3.9f)));
  // 1,000 units across at z = 0: |x| / w = 2.414 * 1000.5 / 4.5 = 537 < 1,023.
  EXPECT_FALSE(needs_clipping_at(kUnitCube, glm::vec3(1000.0f, 0.0f, 0.0f)));
}

TEST(ClipPrediction, ABoxReachingPastTheNearPlaneOrTheBandMayNeedIt) {
  // Near face at z = 4.95: w = 0.05, behind the near plane (0.1).
  EXPECT_TRUE(needs_clipping_at(kUnitCube, glm::vec3(0.0f, 0.0f, 4.45f)));
  // Near face at z = 4.9: w = 0.1, on the plane (within the margin counts as crossing).
  EXPECT_TRUE(needs_clipping_at(kUnitCube, glm::vec3(0.0f, 0.0f, 4.4f)));
  // Behind the camera altogether.
  EXPECT_TRUE(needs_clipping_at(kUnitCube, glm::vec3(0.0f, 0.0f, 8.0f)));
  // 2,000 units across at z = 0: 2.414 * 2000 / 5.5 = 878 at the far face, but at the near
  // face 2.414 * 2000.5 / 4.5 = 1,073 > 1,023.
  EXPECT_TRUE(needs_clipping_at(kUnitCube, glm::vec3(2000.0f, 0.0f, 0.0f)));
  EXPECT_TRUE(needs_clipping_at(kUnitCube, glm::vec3(0.0f, -2000.0f, 0.0f)));
  // A transform that is not finite.
  const double inf = std::numeric_limits<double>::infinity();
  glm::dmat4 broken(1.0);
  broken[3][0] = inf;
  EXPECT_TRUE(may_need_clipping(kUnitCube, default_clip_from_world(), broken, 0.1, kBand));
}

class ClipPass : public test::VulkanTest {};

TEST_F(ClipPass, LeftOutOfFramesWithNothingToClipAndKeptInTheOthers) {
  // The default scene lies well in front of its camera: no clip pass, nothing clipped, one
  // attempt (a missed prediction would have redone the frame).
  Renderer renderer(context(), {});
  const Frame spheres = render(renderer, make_builtin_scene("spheres"), 64, 64);
  EXPECT_EQ(spheres.stats.clipped, 0u);
  EXPECT_EQ(spheres.stats.attempts, 1u);
  ASSERT_TRUE(spheres.stats.has_timestamps);
  EXPECT_EQ(spheres.stats.pass_ms[size_t(Pass::clip)], 0.0);

  // A triangle from in front of the camera to behind it, below the view axis: clipped, in one
  // attempt, and drawn.
  Scene crossing;
  Mesh mesh;
  mesh.positions = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, -0.2f, 10.0f}};
  mesh.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
  mesh.uvs.assign(3, glm::vec2(0.0f));
  mesh.indices = {0, 2, 1};  // facing the camera, which is above its plane
  crossing.meshes = {mesh};
  crossing.materials = {Material{}};
  crossing.objects = {{0, 0, glm::mat4(1.0f)}};
  const Frame clipped = render(renderer, crossing, 64, 64);
  EXPECT_EQ(clipped.stats.clipped, 1u);
  EXPECT_EQ(clipped.stats.attempts, 1u);
  EXPECT_GT(clipped.stats.raster_triangles, 0u);
}

}  // namespace
}  // namespace tessera
