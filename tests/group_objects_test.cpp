// Setup's object search starts from group_objects (compute/scene_upload.h): the object slot that
// holds every TS_TRIANGLE_GROUP-th triangle-instance id. Checked against object_of_triangle
// (core/pick.h, a binary search over the whole numbering) on numberings of objects smaller and
// larger than a group, and through the compute path against the reference renderer on a scene
// of many 12-triangle cubes (a group spans about 21 of them) among larger spheres.
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "compute/scene_upload.h"
#include "core/mesh.h"
#include "core/pick.h"
#include "tests/accuracy_support.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

// Slots numbered in scene order, with the given triangle counts (all > 0, as number_objects
// leaves out objects without triangles).
ObjectNumbering numbering_of(const std::vector<uint64_t>& counts) {
  ObjectNumbering n;
  for (size_t i = 0; i < counts.size(); ++i) {
    n.objects.push_back(uint32_t(i));
    n.first_triangle.push_back(n.triangle_count);
    n.triangle_count += counts[i];
  }
  return n;
}

TEST(GroupObjects, HoldTheObjectOfEachGroupsFirstId) {
  static_assert(TS_TRIANGLE_GROUP == 256u, "the hand-made cases below assume groups of 256");
  // Ids 0, 256, 512 and 768 lie in objects starting at 0, 100, 300 and 600.
  EXPECT_EQ(group_objects(numbering_of({100, 200, 300, 400})), (std::vector<uint32_t>{0, 1, 2, 3}));
  // A group's first id on an object's first triangle belongs to that object.
  EXPECT_EQ(group_objects(numbering_of({256, 256, 1})), (std::vector<uint32_t>{0, 1, 2}));
  // Objects smaller than a group: entries skip over them.
  EXPECT_EQ(group_objects(numbering_of(std::vector<uint64_t>(100, 12))),
            (std::vector<uint32_t>{0, 21, 42, 64, 85}));
  EXPECT_TRUE(group_objects(numbering_of({})).empty());
}

TEST(GroupObjects, AgreeWithObjectOfTriangleOnRandomNumberings) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<uint64_t> counts(1 + rng() % 300);
    // Sizes from 1 triangle to several groups, so that groups hold many objects and objects
    // many groups.
    for (uint64_t& c : counts) c = 1 + (rng() % 4 == 0 ? rng() % 2000 : rng() % 20);
    const ObjectNumbering n = numbering_of(counts);
    const std::vector<uint32_t> groups = group_objects(n);
    ASSERT_EQ(groups.size(), (n.triangle_count + TS_TRIANGLE_GROUP - 1) / TS_TRIANGLE_GROUP);
    for (size_t k = 0; k < groups.size(); ++k) {
      ASSERT_EQ(groups[k], object_of_triangle(n, k * TS_TRIANGLE_GROUP)) << "group " << k;
    }
  }
}

class GroupObjectsOnDevice : public test::VulkanTest {};

// 600 cubes and 30 spheres of 224 and 960 triangles on an interleaved grid: setup finds every
// triangle's object through the table (searching among the cubes, walking among the spheres),
// so a wrong bound would draw a triangle of another object or in the wrong place, which the
// reference's ownership would show.
TEST_F(GroupObjectsOnDevice, ManySmallObjectsAmongLargeOnesMatchTheReference) {
  Scene s;
  s.camera.position = {0.0f, 0.0f, 14.0f};
  s.meshes.push_back(make_cube());
  s.meshes.push_back(make_uv_sphere(16, 8));
  s.meshes.push_back(make_uv_sphere(32, 16));
  s.materials.push_back({});
  int i = 0;
  for (int y = 0; y < 21; ++y) {
    for (int x = 0; x < 30; ++x, ++i) {
      const uint32_t mesh = i % 21 == 5 ? 1u : i % 21 == 15 ? 2u : 0u;
      const glm::vec3 at((float(x) - 14.5f) * 0.4f, (float(y) - 10.0f) * 0.4f, 0.0f);
      glm::mat4 m = glm::translate(glm::mat4(1.0f), at);
      m = glm::rotate(m, 0.3f * float(i), glm::vec3(1.0f, 1.0f, 0.0f));
      s.objects.push_back({mesh, 0, glm::scale(m, glm::vec3(0.15f))});
    }
  }
  Light l;
  l.position = {2.0f, 3.0f, 10.0f};
  l.intensity = 300.0f;
  s.lights.push_back(l);
  // Batches of 1001 triangles start off the groups' bounds and off every subgroup size's
  // multiples, so that subgroups' ids reach into the next group.
  for (uint32_t batch : {0u, 1001u}) {
    SCOPED_TRACE("batches of " + std::to_string(batch) + " triangles (0: one batch)");
    const test::AccuracyReport r = test::compare_with_reference(
        context(), s, 320, 240, "group_objects_many_small_" + std::to_string(batch),
        {.max_batch_triangles = batch});
    EXPECT_GT(r.covered, 320u * 240u / 4u) << "the objects should cover much of the image";
    test::expect_meets_bars(r);
  }
}

}  // namespace
}  // namespace tessera
