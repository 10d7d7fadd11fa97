// Picking (core/pick.h): visibility keys to objects through hand-built numberings.
#include <bit>

#include <gtest/gtest.h>

#include "core/check.h"
#include "core/mesh.h"
#include "core/pick.h"

namespace tessera {
namespace {

// The key the rasterizer writes (shaders/raster_common.glsl): inverted depth bits above the id.
uint64_t key(float depth, uint32_t id) {
  return (uint64_t(~std::bit_cast<uint32_t>(depth)) << 32) | id;
}

TEST(Pick, KeysGiveTheirTriangleAndTheBackgroundNone) {
  EXPECT_EQ(triangle_of_key(key(0.5f, 7)), 7u);
  EXPECT_EQ(triangle_of_key(key(1.0f, 0)), 0u);
  EXPECT_EQ(triangle_of_key(key(1e-30f, 0xFFFFFFFEu)), 0xFFFFFFFEu);
  EXPECT_EQ(triangle_of_key(kEmptyVisibilityKey), std::nullopt);
}

TEST(Pick, TrianglesMapToTheObjectThatOwnsThem) {
  // Numbering order 2, 0, 3 (object 1 has no triangles and is not numbered): object 2 owns
  // ids 0..9, object 0 ids 10..10, object 3 ids 11..14.
  ObjectNumbering n;
  n.objects = {2, 0, 3};
  n.first_triangle = {0, 10, 11};
  n.triangle_count = 15;
  const uint32_t expected[15] = {2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 0, 3, 3, 3, 3};
  for (uint32_t id = 0; id < 15; ++id) {
    EXPECT_EQ(object_of_triangle(n, id), expected[id]) << "triangle " << id;
    EXPECT_EQ(pick_object(n, key(0.25f, id)), expected[id]) << "triangle " << id;
  }
  EXPECT_EQ(pick_object(n, kEmptyVisibilityKey), std::nullopt);
}

TEST(Pick, AnIdOutsideTheNumberingIsAnError) {
  ObjectNumbering n;
  n.objects = {0};
  n.first_triangle = {0};
  n.triangle_count = 12;
  EXPECT_THROW(object_of_triangle(n, 12), Error);
  EXPECT_THROW(pick_object(n, key(0.5f, 100)), Error);
  EXPECT_THROW(pick_object(ObjectNumbering{}, key(0.5f, 0)), Error);
}

TEST(Pick, AgreesWithNumberObjects) {
  // Two cubes (12 triangles) and an empty mesh between them: number_objects sorts by content,
  // and whatever its order, each id range maps back to an object with that many triangles.
  Scene s;
  s.meshes = {make_cube(), Mesh{}, make_plane(2, 1)};  // 12, 0, 4 triangles
  s.materials = {Material{}};
  s.objects = {Object{.mesh = 2}, Object{.mesh = 1}, Object{.mesh = 0}};
  const ObjectNumbering n = number_objects(s);
  ASSERT_EQ(n.triangle_count, 16u);
  uint32_t per_object[3] = {0, 0, 0};
  for (uint32_t id = 0; id < 16; ++id) ++per_object[object_of_triangle(n, id)];
  EXPECT_EQ(per_object[0], 4u);
  EXPECT_EQ(per_object[1], 0u);
  EXPECT_EQ(per_object[2], 12u);
}

}  // namespace
}  // namespace tessera
