// The viewer's orbit camera (core/orbit_camera.h): expected values from the documented
// formulas, worked by hand, and pan checked through the renderers' own projection.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/mesh.h"
#include "core/orbit_camera.h"

namespace tessera {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

void expect_near(glm::vec3 a, glm::vec3 b, float tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(OrbitCamera, ToCameraPlacesTheEyeByYawAndPitch) {
  OrbitCamera o;  // yaw 0, pitch 0, distance 5: the default Camera, on +z looking down -z
  const Camera c = to_camera(o);
  EXPECT_EQ(c, Camera{});
  o.target = {1, 0, 0};
  o.distance = 2;
  o.yaw = kPi / 2;  // toward +x
  expect_near(to_camera(o).position, {3, 0, 0}, 1e-6f);
  o.yaw = 0;
  o.pitch = kPi / 4;  // raised: (0, 2 sin 45, 2 cos 45) from the target
  expect_near(to_camera(o).position, {1, std::sqrt(2.0f), std::sqrt(2.0f)}, 1e-6f);
  o.up = {0, 0, 1};  // z up: back is then +x, right = up x back = +y
  o.pitch = 0;
  o.yaw = kPi / 2;
  expect_near(to_camera(o).position, {1, 2, 0}, 1e-6f);
}

TEST(OrbitCamera, FromCameraRoundTrips) {
  Camera a;
  a.position = {1.5f, 2.25f, -3.0f};
  a.target = {0.25f, -0.5f, 0.75f};
  a.vertical_fov = glm::radians(60.0f);
  a.near_plane = 0.01f;
  Camera b;
  b.position = {0.0f, -4.0f, 10.0f};
  b.target = {0.0f, 0.0f, 0.0f};
  b.up = {0.0f, 0.0f, 2.0f};  // not unit, not +y: copied as it is
  for (const Camera& c : {a, b, Camera{}}) {
    const Camera back = to_camera(from_camera(c));
    EXPECT_EQ(back.target, c.target);
    EXPECT_EQ(back.up, c.up);
    EXPECT_EQ(back.vertical_fov, c.vertical_fov);
    EXPECT_EQ(back.near_plane, c.near_plane);
    expect_near(back.position, c.position, 1e-5f * glm::length(c.position - c.target));
  }
  // And the other way: yaw, pitch and distance come back.
  OrbitCamera o;
  o.yaw = -2.0f;
  o.pitch = 0.7f;
  o.distance = 3.5f;
  o.target = {4, 5, 6};
  const OrbitCamera r = from_camera(to_camera(o));
  EXPECT_NEAR(r.yaw, o.yaw, 1e-5f);
  EXPECT_NEAR(r.pitch, o.pitch, 1e-5f);
  EXPECT_NEAR(r.distance, o.distance, 1e-5f);
}

TEST(OrbitCamera, OrbitTurnsByPixelsOverHeight) {
  OrbitCamera o;  // pi radians per viewport height
  const Viewport v{800, 600};
  orbit(o, 150.0f, 60.0f, v);
  EXPECT_NEAR(o.yaw, -150.0f * kPi / 600.0f, 1e-6f);  // -pi/4
  EXPECT_NEAR(o.pitch, 60.0f * kPi / 600.0f, 1e-6f);  // pi/10
  o.orbit_radians_per_height = 1.0f;
  orbit(o, -300.0f, 0.0f, v);
  EXPECT_NEAR(o.yaw, -kPi / 4 + 0.5f, 1e-6f);
  // Pitch stops short of the poles.
  orbit(o, 0.0f, 1e6f, v);
  EXPECT_EQ(o.pitch, kMaxOrbitPitch);
  orbit(o, 0.0f, -1e7f, v);
  EXPECT_EQ(o.pitch, -kMaxOrbitPitch);
  EXPECT_THROW(orbit(o, 1.0f, 1.0f, Viewport{800, 0}), Error);
}

// Pixel of world point p seen by `camera` in a w x h image (pixel centres at half integers).
glm::vec2 pixel_of(const Camera& camera, glm::vec3 p, float w, float h) {
  const glm::vec4 clip =
      projection_matrix(camera, w / h) * view_matrix(camera) * glm::vec4(p, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return (ndc * 0.5f + 0.5f) * glm::vec2(w, h);
}

TEST(OrbitCamera, PanKeepsThePointUnderTheCursor) {
  OrbitCamera o;
  o.target = {0.5f, 1.0f, -2.0f};
  o.distance = 7.0f;
  o.yaw = 0.6f;
  o.pitch = -0.3f;
  o.vertical_fov = glm::radians(50.0f);
  const Viewport v{640, 480};
  const glm::vec3 grabbed = o.target;  // at the target's depth, under the centre pixel
  const glm::vec2 before = pixel_of(to_camera(o), grabbed, 640, 480);
  expect_near(glm::vec3(before, 0), {320, 240, 0}, 1e-3f);
  pan(o, 37.0f, -22.0f, v);
  const glm::vec2 after = pixel_of(to_camera(o), grabbed, 640, 480);
  EXPECT_NEAR(after.x, 320.0f + 37.0f, 1e-3f);
  EXPECT_NEAR(after.y, 240.0f - 22.0f, 1e-3f);
  EXPECT_EQ(o.distance, 7.0f);
}

TEST(OrbitCamera, ZoomIsMultiplicative) {
  OrbitCamera o;  // distance 5, ratio 0.9 per step
  zoom(o, 2.0f);
  EXPECT_NEAR(o.distance, 5.0f * 0.81f, 1e-6f);
  zoom(o, -3.0f);
  EXPECT_NEAR(o.distance, 5.0f / 0.9f, 1e-5f);
  zoom(o, 1e6f);
  EXPECT_EQ(o.distance, kMinOrbitDistance);
  zoom(o, -1e6f);
  EXPECT_EQ(o.distance, kMaxOrbitDistance);
  EXPECT_EQ(o.target, glm::vec3(0.0f));
}

TEST(OrbitCamera, FlyMovesTargetAndEyeTogether) {
  OrbitCamera o;  // looking down -z from distance 5; 1 distance per second
  fly(o, FlyKeys{.forward = true}, 1.0f);
  expect_near(o.target, {0, 0, -5}, 1e-5f);
  expect_near(to_camera(o).position, {0, 0, 0}, 1e-5f);
  o.target = glm::vec3(0.0f);
  fly(o, FlyKeys{.forward = true, .right = true}, 0.5f);  // diagonal, not faster
  expect_near(o.target, glm::vec3(1, 0, -1) * (2.5f / std::sqrt(2.0f)), 1e-5f);
  o.target = glm::vec3(0.0f);
  fly(o, FlyKeys{.down = true}, 0.2f);
  expect_near(o.target, {0, -1, 0}, 1e-6f);
  fly(o, FlyKeys{.forward = true, .back = true}, 1.0f);  // cancel
  expect_near(o.target, {0, -1, 0}, 1e-6f);
  EXPECT_THROW(fly(o, FlyKeys{}, -1.0f), Error);
}

TEST(OrbitCamera, FrameSceneFitsTheBoundingSphere) {
  Scene s;
  s.meshes = {make_uv_sphere(64, 32)};
  s.materials = {Material{}};
  s.objects = {Object{}};
  OrbitCamera o;
  o.yaw = 0.4f;
  o.vertical_fov = glm::radians(45.0f);
  ASSERT_TRUE(frame_scene(o, s, 16.0f / 9.0f, 0.1f));
  // A unit sphere just fits the vertical field of view at 1 / sin(fov / 2).
  EXPECT_NEAR(o.distance, 1.0f / std::sin(glm::radians(22.5f)), 1e-5f);
  expect_near(o.target, glm::vec3(0.0f), 1e-6f);
  EXPECT_EQ(o.yaw, 0.4f);
  // Portrait: the horizontal half angle atan(tan(22.5 deg) / 2) is the narrower.
  ASSERT_TRUE(frame_scene(o, s, 0.5f, 0.1f));
  EXPECT_NEAR(o.distance, 1.0f / std::sin(std::atan(std::tan(glm::radians(22.5f)) * 0.5f)), 1e-5f);
  // Two spheres of radius 1 at x = -2 and x = 2 make one of radius 3 about the origin.
  s.objects = {Object{.transform = glm::translate(glm::mat4(1.0f), {-2, 0, 0})},
               Object{.transform = glm::translate(glm::mat4(1.0f), {2, 0, 0})}};
  ASSERT_TRUE(frame_scene(o, s, 1.0f, 0.1f));
  EXPECT_NEAR(o.distance, 3.0f / std::sin(glm::radians(22.5f)), 1e-4f);
  expect_near(o.target, glm::vec3(0.0f), 1e-6f);
  // Scaled by 2 and moved: radius 2 about (3, 0, 0).
  s.objects = {
      Object{.transform = glm::scale(glm::translate(glm::mat4(1.0f), {3, 0, 0}), glm::vec3(2.0f))}};
  ASSERT_TRUE(frame_scene(o, s, 1.0f, 0.1f));
  EXPECT_NEAR(o.distance, 2.0f / std::sin(glm::radians(22.5f)), 1e-4f);
  expect_near(o.target, {3, 0, 0}, 1e-5f);
  // Nothing to frame: unchanged.
  s.objects.clear();
  const OrbitCamera kept = o;
  EXPECT_FALSE(frame_scene(o, s, 1.0f, 0.1f));
  EXPECT_EQ(o.distance, kept.distance);
  EXPECT_THROW(frame_scene(o, s, 0.0f, 0.1f), Error);
  EXPECT_THROW(frame_scene(o, s, 1.0f, 0.0f), Error);
}

// F in the viewer: the near plane never cuts into what is framed, and returns to the one
// preferred (the scene's camera's) where there is room. Worked by hand at a 45 degree field
// of view, 1 / sin(22.5 deg) = 2.6131259: a unit sphere is framed from 2.6131259, a gap of
// 1.6131259, and half of it is beyond 0.1 m; a sphere of radius 1 mm from 0.0026131, a gap of
// 0.0016131, so the near plane is 0.00080656.
TEST(OrbitCamera, FramingKeepsTheNearPlaneInFrontOfTheSphere) {
  OrbitCamera o;
  o.vertical_fov = glm::radians(45.0f);
  ASSERT_TRUE(frame_sphere(o, {glm::vec3(0.0f), 1.0f}, 1.0f, 0.1f));
  EXPECT_EQ(o.near_plane, 0.1f);
  ASSERT_TRUE(frame_sphere(o, {glm::vec3(5.0f), 0.001f}, 1.0f, 0.1f));
  EXPECT_NEAR(o.distance, 0.0026131259f, 1e-8f);
  EXPECT_NEAR(o.near_plane, 0.00080656f, 1e-8f);
  // The sphere's nearest point, distance - radius, is beyond the near plane.
  EXPECT_GT(o.distance - 0.001f, o.near_plane);
  ASSERT_TRUE(frame_sphere(o, {glm::vec3(0.0f), 1.0f}, 1.0f, 0.1f));
  EXPECT_EQ(o.near_plane, 0.1f);
  // A scene camera's own near plane is kept where there is room.
  ASSERT_TRUE(frame_sphere(o, {glm::vec3(0.0f), 1.0f}, 1.0f, 0.5f));
  EXPECT_EQ(o.near_plane, 0.5f);
}

// A scene of one box from `lo` to `hi`, its 8 corners the mesh's vertices (as a model file
// would give them: no transform to widen its bounding sphere).
Scene box_scene(glm::vec3 lo, glm::vec3 hi) {
  Mesh box;
  for (int i = 0; i < 8; ++i) {
    box.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
    box.normals.push_back({0, 0, 1});
    box.uvs.push_back({0, 0});
  }
  box.indices = {0, 1, 3, 0, 3, 2};
  Scene s;
  s.meshes = {box};
  s.materials = {Material{}};
  s.objects = {Object{}};
  return s;
}

// The largest |x| and |y| in normalized device coordinates of the box's corners, as the
// renderers project them (core/scene.h).
glm::vec2 projected_extent(const Scene& s, const Camera& c, float aspect) {
  const glm::mat4 clip = projection_matrix(c, aspect) * view_matrix(c);
  glm::vec2 extent(0.0f);
  for (glm::vec3 p : s.meshes[0].positions) {
    const glm::vec4 q = clip * glm::vec4(p, 1.0f);
    EXPECT_GT(q.w, c.near_plane) << "corner in front of the near plane";
    extent = glm::max(extent, glm::abs(glm::vec2(q) / q.w));
  }
  return extent;
}

// A model given as a scene is seen from +z with its bounding sphere just inside the narrower
// field of view. Expected distances are the sphere's radius over sin(22.5 degrees) =
// 0.38268343, worked out by hand for each box.
TEST(OrbitCamera, FramedCameraFitsBoxesOfEveryShape) {
  // A unit cube about the origin: radius sqrt(0.75) = 0.8660254, distance 2.2630334. Its
  // front face (z = 0.5, depth 1.7630334) reaches 0.5 / (1.7630334 tan 22.5 deg) = 0.6846761
  // of the way to each edge of a square image.
  Scene s = box_scene(glm::vec3(-0.5f), glm::vec3(0.5f));
  Camera c = framed_camera(s, 1.0f);
  expect_near(c.target, glm::vec3(0.0f), 1e-6f);
  expect_near(c.position, {0, 0, 2.2630334f}, 1e-5f);
  EXPECT_EQ(c.up, glm::vec3(0, 1, 0));
  EXPECT_NEAR(c.vertical_fov, glm::radians(45.0f), 1e-7f);
  EXPECT_EQ(c.near_plane, 0.1f);  // the default: the cube is 1.4 m beyond it
  glm::vec2 extent = projected_extent(s, c, 1.0f);
  EXPECT_NEAR(extent.x, 0.6846761f, 1e-4f);
  EXPECT_NEAR(extent.y, 0.6846761f, 1e-4f);

  // Off centre, from (1, 2, -1) to (3, 4, 1): centre (2, 3, 0), radius sqrt(3) = 1.7320508,
  // distance 4.5260669 along +z from the centre.
  s = box_scene({1, 2, -1}, {3, 4, 1});
  c = framed_camera(s, 1.0f);
  expect_near(c.target, {2, 3, 0}, 1e-6f);
  expect_near(c.position, {2, 3, 4.5260669f}, 1e-5f);
  extent = projected_extent(s, c, 1.0f);
  EXPECT_NEAR(extent.x, 0.6846761f, 1e-4f);  // the unit cube's view, twice as large and far

  // 100 m long and 1 m thick along x: radius sqrt(50^2 + 0.5^2 + 0.5^2) = 50.0049998,
  // distance 130.6693615; its ends, at depth 130.1693615, are at x = +-0.9273356 of the
  // width: within the image, not cut off.
  s = box_scene({-50, -0.5f, -0.5f}, {50, 0.5f, 0.5f});
  c = framed_camera(s, 1.0f);
  expect_near(c.position, {0, 0, 130.6693615f}, 1e-3f);
  extent = projected_extent(s, c, 1.0f);
  EXPECT_NEAR(extent.x, 0.9273356f, 1e-4f);
  EXPECT_LT(extent.y, 0.01f);
  // In a portrait image (aspect 0.5) the horizontal half angle atan(tan(22.5 deg) / 2) =
  // 11.7010 deg, sine 0.2028010, is the narrower: distance 246.5693171.
  c = framed_camera(s, 0.5f);
  expect_near(c.position, {0, 0, 246.5693171f}, 1e-2f);
  EXPECT_LT(projected_extent(s, c, 0.5f).x, 1.0f);

  // A 2 mm cube would lie inside the default near plane (0.1 m): radius 0.0017321, distance
  // 0.0045261, so the near plane is half the gap between eye and sphere, 0.0013970.
  s = box_scene(glm::vec3(-0.001f), glm::vec3(0.001f));
  c = framed_camera(s, 1.0f);
  expect_near(c.position, {0, 0, 0.0045261f}, 1e-7f);
  EXPECT_NEAR(c.near_plane, 0.0013970f, 1e-7f);
  extent = projected_extent(s, c, 1.0f);
  EXPECT_NEAR(extent.x, 0.6846761f, 1e-3f);

  // A 20 um cube (radius 1.7320508e-5, distance 4.5260669e-5) and a 2e9 m one (radius
  // 1.7320508e9, distance 4.5260669e9) are framed as the unit cube is, not held at the old
  // orbit limits of 1e-4 m (small in the view) and 1e9 m (the eye inside the model).
  for (const float half : {1e-5f, 1e9f}) {
    s = box_scene(glm::vec3(-half), glm::vec3(half));
    c = framed_camera(s, 1.0f);
    EXPECT_NEAR(c.position.z / half, 4.5260669f, 1e-5f) << half;
    EXPECT_NEAR(projected_extent(s, c, 1.0f).x, 0.6846761f, 1e-3f) << half;
  }

  // Nothing to frame: the default camera.
  s.objects.clear();
  EXPECT_EQ(framed_camera(s, 1.0f), Camera{});
}

}  // namespace
}  // namespace tessera
