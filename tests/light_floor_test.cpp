// Lights nearer an object than the shading's 1 cm distance floor (core/light_floor.h): the
// distance from a light to an object's placed box, worked by hand below, and which lights the
// scene-level search finds. The notes that `render` and `view` print from it are tested with
// the other notes (scene_file_test.cpp, SceneFileCli).
#include <cmath>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/light_floor.h"
#include "core/mesh.h"
#include "core/scene_file.h"

namespace tessera {
namespace {

const MeshBox kUnitCube{glm::vec3(-0.5f), glm::vec3(0.5f)};
const glm::dmat4 kIdentity(1.0);

TEST(LightFloor, DistanceToAnAxisAlignedBox) {
  // Beyond a face, an edge and a corner of the cube of side 1 about the origin.
  EXPECT_DOUBLE_EQ(distance_to_placed_box(kUnitCube, kIdentity, {2.0, 0.0, 0.0}), 1.5);
  EXPECT_DOUBLE_EQ(distance_to_placed_box(kUnitCube, kIdentity, {1.5, 1.5, 0.2}), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(distance_to_placed_box(kUnitCube, kIdentity, {-1.5, 1.5, -1.5}), std::sqrt(3.0));
  // Inside and on a face.
  EXPECT_EQ(distance_to_placed_box(kUnitCube, kIdentity, {0.1, -0.2, 0.3}), 0.0);
  EXPECT_EQ(distance_to_placed_box(kUnitCube, kIdentity, {0.5, 0.0, 0.0}), 0.0);
  // Translated by (10, 0, 0) and scaled by (2, 1, 1e-6): x in [9, 11], z in +-5e-7.
  const glm::dmat4 thin = glm::scale(glm::translate(kIdentity, {10.0, 0.0, 0.0}), {2.0, 1.0, 1e-6});
  EXPECT_NEAR(distance_to_placed_box(kUnitCube, thin, {10.0, 0.0, 1e-3}), 1e-3 - 5e-7, 1e-15);
  EXPECT_DOUBLE_EQ(distance_to_placed_box(kUnitCube, thin, {8.0, 0.0, 0.0}), 1.0);
}

// The box as the transform places it, not the world-space box around that: rotated 45 degrees
// about z, the cube's side faces lie 0.5 from its centre along (+-1, +-1, 0) / sqrt(2), and
// its vertical edges at (+-sqrt(1/2), 0) and (0, +-sqrt(1/2)).
TEST(LightFloor, DistanceToARotatedBox) {
  const glm::dmat4 turned = glm::rotate(kIdentity, glm::radians(45.0), {0.0, 0.0, 1.0});
  // (0.6, 0.6, 0) is inside the world-space box (x, y within +-0.707) but 0.6 sqrt(2) from the
  // centre along the face's normal.
  EXPECT_NEAR(distance_to_placed_box(kUnitCube, turned, {0.6, 0.6, 0.0}),
              0.6 * std::sqrt(2.0) - 0.5, 1e-15);
  EXPECT_NEAR(distance_to_placed_box(kUnitCube, turned, {1.0, 0.0, 0.0}), 1.0 - std::sqrt(0.5),
              1e-15);
  // Past the edge at (sqrt(1/2), 0) by 1 - sqrt(1/2), and above the top face (z = 0.5) by 0.5.
  EXPECT_NEAR(distance_to_placed_box(kUnitCube, turned, {1.0, 0.0, 1.0}),
              std::sqrt(std::pow(1.0 - std::sqrt(0.5), 2.0) + 0.25), 1e-15);
  EXPECT_EQ(distance_to_placed_box(kUnitCube, turned, {0.3, 0.3, 0.4}), 0.0);
}

// A shear x' = x + y makes the box [0, 1]^3 the parallelepiped (x + y, y, z): its face x = 0
// lies in the plane x' = y', normal (1, -1, 0) / sqrt(2). The point (0, 1, 0.5) lies 1/sqrt(2)
// from it, the foot (0.5, 0.5, 0.5) inside the face; its world-space box (x' in [0, 2]) holds
// the point, and in object space the point is (-1, 1, 0.5), 1 from the box.
TEST(LightFloor, DistanceToAShearedBox) {
  const MeshBox box{glm::vec3(0.0f), glm::vec3(1.0f)};
  glm::dmat4 shear(1.0);
  shear[1][0] = 1.0;  // column y, row x: x' = x + y
  EXPECT_NEAR(distance_to_placed_box(box, shear, {0.0, 1.0, 0.5}), std::sqrt(0.5), 1e-15);
  EXPECT_EQ(distance_to_placed_box(box, shear, {1.5, 1.0, 0.5}), 0.0);  // (0.5, 1, 0.5) inside
}

// A flat box (make_plane's: z = 0) has no inside: a point above it is at its height, one beside
// it at the distance to its edge.
TEST(LightFloor, DistanceToAFlatOrEmptyBox) {
  const MeshBox plane{glm::vec3(-1.0f, -1.0f, 0.0f), glm::vec3(1.0f, 1.0f, 0.0f)};
  EXPECT_DOUBLE_EQ(distance_to_placed_box(plane, kIdentity, {0.2, 0.3, 0.005}), 0.005);
  EXPECT_EQ(distance_to_placed_box(plane, kIdentity, {0.2, 0.3, 0.0}), 0.0);
  EXPECT_DOUBLE_EQ(distance_to_placed_box(plane, kIdentity, {2.0, 0.0, 0.0}), 1.0);
  EXPECT_DOUBLE_EQ(distance_to_placed_box(plane, kIdentity, {1.5, 0.0, 0.5}), std::sqrt(0.5));
  // Turned to the floor (lights.json's): y = 0.
  const glm::dmat4 floor = glm::rotate(kIdentity, glm::radians(-90.0), {1.0, 0.0, 0.0});
  EXPECT_NEAR(distance_to_placed_box(plane, floor, {0.5, 0.004, -0.5}), 0.004, 1e-15);
  EXPECT_EQ(distance_to_placed_box(MeshBox{}, kIdentity, {0.0, 0.0, 0.0}),
            std::numeric_limits<double>::infinity());
}

Light point_at(glm::vec3 position) {
  Light light;
  light.position = position;
  return light;
}

// A micrometre scene: cubes of side 2 um (make_cube scaled by 1e-6) at the origin (object 0)
// and at x = 10 um (object 1), and a cube of side 2 m at x = 10 m (object 2).
Scene micro_scene() {
  Scene scene;
  scene.meshes.push_back(make_cube());
  scene.meshes.push_back(Mesh{});  // no triangles: draws nothing, so nothing to light
  scene.materials.push_back(Material{});
  const auto place = [&](uint32_t mesh, glm::vec3 at, float scale) {
    Object o;
    o.mesh = mesh;
    o.transform = glm::scale(glm::translate(glm::mat4(1.0f), at), glm::vec3(scale));
    scene.objects.push_back(o);
  };
  place(0, {0.0f, 0.0f, 0.0f}, 1e-6f);
  place(0, {1e-5f, 0.0f, 0.0f}, 1e-6f);
  place(0, {10.0f, 0.0f, 0.0f}, 1.0f);
  return scene;
}

TEST(LightFloor, FindsTheLightsNearerThanOneCentimetre) {
  Scene scene = micro_scene();
  // 1e-6 m above object 1's top (y = 1e-6), and sqrt(9^2 + 1^2) um from object 0's corner edge:
  // the nearest object is 1, not the first one within 1 cm.
  scene.lights.push_back(point_at({1e-5f, 2e-6f, 0.0f}));
  Light sun;
  sun.kind = LightKind::directional;
  scene.lights.push_back(sun);  // no position, no floor
  Light classic = point_at({0.0f, 0.0f, 0.0f});
  classic.falloff = Falloff::classic;  // floors its denominator, not the distance
  scene.lights.push_back(classic);
  scene.lights.push_back(point_at({0.0f, 0.5f, 0.0f}));  // 0.5 m away
  Light spot = point_at({0.0f, 0.0f, 3e-6f});            // 2 um from object 0
  spot.kind = LightKind::spot;
  scene.lights.push_back(spot);
  Light short_range = point_at({0.0f, 0.002f, 0.0f});  // ~2 mm away, beyond its 1 mm range
  short_range.range = 1e-3f;
  scene.lights.push_back(short_range);
  short_range.position.y = 5e-4f;  // ~0.5 mm away, within it
  scene.lights.push_back(short_range);
  // Either side of 1 cm from object 2's top face (y = 1), in exactly representable steps.
  scene.lights.push_back(point_at({10.0f, 1.015625f, 0.0f}));
  scene.lights.push_back(point_at({10.0f, 1.0078125f, 0.0f}));
  validate_scene(scene);
  const NearLights near = lights_within_floor(scene);
  EXPECT_EQ(near.count, 4u);  // lights 0, 4, 6 and 8
  EXPECT_EQ(near.light, 0u);
  EXPECT_EQ(near.object, 1u);
  EXPECT_NEAR(near.distance, 1e-6, 1e-12);
  // Without light 0 the first is the spot, 2 um above object 0 (z = 1e-6 and 3e-6).
  scene.lights.erase(scene.lights.begin());
  const NearLights rest = lights_within_floor(scene);
  EXPECT_EQ(rest.count, 3u);
  EXPECT_EQ(rest.light, 3u);
  EXPECT_EQ(rest.object, 0u);
  EXPECT_NEAR(rest.distance, 2e-6, 1e-12);
}

// Inside an object's box is not near its surface: a lamp in the middle of a room (a cube of
// side 10 m, its walls 5 m away), a light inside a unit sphere's box at (0.7, 0.7, 0.7), 0.21 m
// outside the sphere (|p| = 1.212 m, and the mesh's faces lie within the sphere), are not
// noted; a light 5 mm inside a unit sphere's surface is, at 5 mm less the mesh's sag (its
// faces lie up to 1 - cos(pi / 32) = 0.0048 m inside the sphere at the equator's segments).
TEST(LightFloor, InsideTheBoxIsNotNearTheSurface) {
  Scene scene;
  scene.meshes.push_back(make_cube());
  scene.meshes.push_back(make_uv_sphere(64, 32));
  scene.materials.push_back(Material{});
  Object room;
  room.mesh = 0;
  room.transform = glm::scale(glm::mat4(1.0f), glm::vec3(5.0f));
  scene.objects.push_back(room);
  Object ball;
  ball.mesh = 1;
  ball.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -3.0f, 0.0f));
  scene.objects.push_back(ball);
  scene.lights.push_back(point_at({0.0f, 0.0f, 0.0f}));
  scene.lights.push_back(point_at({0.7f, -2.3f, 0.7f}));
  validate_scene(scene);
  EXPECT_EQ(lights_within_floor(scene).count, 0u);
  scene.lights.push_back(point_at({0.995f, -3.0f, 0.0f}));
  const NearLights near = lights_within_floor(scene);
  EXPECT_EQ(near.count, 1u);
  EXPECT_EQ(near.light, 2u);
  EXPECT_EQ(near.object, 1u);
  EXPECT_TRUE(near.exact);
  EXPECT_GT(near.distance, 0.0);
  EXPECT_LE(near.distance, 0.005 + 1e-6);
  EXPECT_GE(near.distance, 0.005 - (1.0 - std::cos(glm::pi<double>() / 32)) - 1e-6);
}

// A light inside an object that draws nothing (its mesh has no triangles) lights nothing of it.
TEST(LightFloor, ObjectsWithoutTrianglesAreLeftOut) {
  Scene scene = micro_scene();
  Mesh dot;
  dot.positions = {{0.0f, 5.0f, 0.0f}};
  dot.normals = {{0.0f, 1.0f, 0.0f}};
  scene.meshes[1] = dot;
  Object o;
  o.mesh = 1;
  scene.objects.push_back(o);
  scene.lights.push_back(point_at({0.0f, 5.0f, 0.0f}));
  validate_scene(scene);
  EXPECT_EQ(lights_within_floor(scene).count, 0u);
}

// No scene Tessera ships (the built-in ones, made in code or read from scenes/, and the
// examples) puts a light within 1 cm of an object: their renders print no such note.
TEST(LightFloor, ShippedScenesHaveNoLightWithinTheFloor) {
  for (const BuiltinSceneInfo& info : builtin_scenes())
    EXPECT_EQ(lights_within_floor(make_builtin_scene(info.name)).count, 0u) << info.name;
  for (const char* folder : {TESSERA_SCENES_DIR, TESSERA_EXAMPLE_SCENES_DIR}) {
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      if (entry.path().extension() != ".json") continue;
      EXPECT_EQ(lights_within_floor(load_scene_file(entry.path().string()).scene).count, 0u)
          << entry.path();
    }
  }
}

}  // namespace
}  // namespace tessera
