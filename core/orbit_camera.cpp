#include "core/orbit_camera.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/check.h"

namespace tessera {
namespace {

float viewport_height(Viewport viewport) {
  if (viewport.width == 0 || viewport.height == 0)
    throw Error("the camera cannot be dragged in an empty viewport");
  return float(viewport.height);
}

glm::vec3 orbit_offset(const OrbitCamera& c) {
  const OrbitBasis b = orbit_basis(c.up);
  return std::cos(c.pitch) * (std::sin(c.yaw) * b.right + std::cos(c.yaw) * b.back) +
         std::sin(c.pitch) * b.up;
}

// The view's right and up axes (the camera looks along -offset).
struct ViewAxes {
  glm::vec3 forward, right, up;
};
ViewAxes view_axes(const OrbitCamera& c) {
  ViewAxes v;
  v.forward = -orbit_offset(c);
  v.right = glm::normalize(glm::cross(v.forward, c.up));
  v.up = glm::cross(v.right, v.forward);
  return v;
}

float clamp_distance(float d) {
  return std::clamp(d, kMinOrbitDistance, kMaxOrbitDistance);
}

}  // namespace

OrbitBasis orbit_basis(glm::vec3 up) {
  OrbitBasis b;
  b.up = glm::normalize(up);
  // +z made orthogonal to up, unless up is (nearly) along z: then +x.
  glm::vec3 back = glm::vec3(0.0f, 0.0f, 1.0f) - b.up * b.up.z;
  if (glm::dot(back, back) < 1e-6f) back = glm::vec3(1.0f, 0.0f, 0.0f) - b.up * b.up.x;
  b.back = glm::normalize(back);
  b.right = glm::cross(b.up, b.back);
  return b;
}

Camera to_camera(const OrbitCamera& orbit) {
  Camera c;
  c.target = orbit.target;
  c.position = orbit.target + orbit.distance * orbit_offset(orbit);
  c.up = orbit.up;
  c.vertical_fov = orbit.vertical_fov;
  c.near_plane = orbit.near_plane;
  return c;
}

OrbitCamera from_camera(const Camera& camera, const OrbitCamera& settings) {
  OrbitCamera o = settings;
  o.target = camera.target;
  o.up = camera.up;
  o.vertical_fov = camera.vertical_fov;
  o.near_plane = camera.near_plane;
  // In double, so that the round trip through to_camera loses only float rounding.
  const glm::dvec3 offset = glm::dvec3(camera.position) - glm::dvec3(camera.target);
  const double distance = glm::length(offset);
  o.distance = float(distance);
  const OrbitBasis b = orbit_basis(camera.up);
  const double along_up = glm::dot(offset, glm::dvec3(b.up)) / distance;
  o.pitch = float(std::asin(std::clamp(along_up, -1.0, 1.0)));
  o.yaw = float(
      std::atan2(glm::dot(offset, glm::dvec3(b.right)), glm::dot(offset, glm::dvec3(b.back))));
  return o;
}

void orbit(OrbitCamera& camera, float dx_pixels, float dy_pixels, Viewport viewport) {
  const float s = camera.orbit_radians_per_height / viewport_height(viewport);
  camera.yaw -= dx_pixels * s;
  camera.pitch = std::clamp(camera.pitch + dy_pixels * s, -kMaxOrbitPitch, kMaxOrbitPitch);
}

void pan(OrbitCamera& camera, float dx_pixels, float dy_pixels, Viewport viewport) {
  const float metres_per_pixel =
      2.0f * camera.distance * std::tan(camera.vertical_fov * 0.5f) / viewport_height(viewport);
  const ViewAxes v = view_axes(camera);
  camera.target += metres_per_pixel * (-dx_pixels * v.right + dy_pixels * v.up);
}

void zoom(OrbitCamera& camera, float steps) {
  camera.distance = clamp_distance(camera.distance * std::pow(camera.zoom_ratio_per_step, steps));
}

void fly(OrbitCamera& camera, const FlyKeys& keys, float seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0f)
    throw Error("fly needs a finite time >= 0 s, not " + std::to_string(seconds));
  const ViewAxes v = view_axes(camera);
  const glm::vec3 world_up = glm::normalize(camera.up);
  glm::vec3 d(0.0f);
  if (keys.forward) d += v.forward;
  if (keys.back) d -= v.forward;
  if (keys.right) d += v.right;
  if (keys.left) d -= v.right;
  if (keys.up) d += world_up;
  if (keys.down) d -= world_up;
  // Opposite keys cancel to (nearly) zero: no direction to normalize.
  if (glm::dot(d, d) < 1e-12f) return;
  camera.target +=
      glm::normalize(d) * (camera.fly_distances_per_second * camera.distance * seconds);
}

namespace {

// The sphere about the centre of the vertex bounding box of `mesh` through its farthest vertex
// (radius < 0 for a mesh without vertices).
BoundingSphere mesh_sphere(const Mesh& mesh) {
  const std::vector<glm::vec3>& p = mesh.positions;
  BoundingSphere s;
  if (p.empty()) return s;
  glm::vec3 lo = p[0], hi = p[0];
  for (const glm::vec3& v : p) lo = glm::min(lo, v), hi = glm::max(hi, v);
  s.centre = 0.5f * (lo + hi);
  s.radius = 0.0f;
  for (const glm::vec3& v : p) s.radius = std::max(s.radius, glm::length(v - s.centre));
  return s;
}

// `s` placed by `transform`: the radius grows by the transform's largest axis scale.
BoundingSphere placed_sphere(const BoundingSphere& s, const glm::mat4& transform) {
  const glm::mat3 m(transform);
  const float scale = std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
  return {glm::vec3(transform * glm::vec4(s.centre, 1.0f)), s.radius * scale};
}

}  // namespace

BoundingSphere scene_bounds(const Scene& scene) {
  std::vector<BoundingSphere> mesh_spheres(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) mesh_spheres[m] = mesh_sphere(scene.meshes[m]);
  std::vector<BoundingSphere> placed;
  for (const Object& o : scene.objects) {
    const BoundingSphere& s = mesh_spheres[o.mesh];
    if (s.radius < 0.0f) continue;
    placed.push_back(placed_sphere(s, o.transform));
  }
  BoundingSphere all;
  if (placed.empty()) return all;
  glm::vec3 lo = placed[0].centre - placed[0].radius, hi = placed[0].centre + placed[0].radius;
  for (const BoundingSphere& s : placed) {
    lo = glm::min(lo, s.centre - s.radius);
    hi = glm::max(hi, s.centre + s.radius);
  }
  all.centre = 0.5f * (lo + hi);
  all.radius = 0.0f;
  for (const BoundingSphere& s : placed)
    all.radius = std::max(all.radius, glm::length(s.centre - all.centre) + s.radius);
  return all;
}

BoundingSphere object_bounds(const Scene& scene, uint32_t object) {
  if (object >= scene.objects.size())
    throw Error("object " + std::to_string(object) + " out of range (the scene has " +
                std::to_string(scene.objects.size()) + ")");
  const Object& o = scene.objects[object];
  const BoundingSphere s = mesh_sphere(scene.meshes[o.mesh]);
  return s.radius < 0.0f ? s : placed_sphere(s, o.transform);
}

bool frame_sphere(OrbitCamera& camera, const BoundingSphere& bounds, float aspect,
                  float preferred_near) {
  if (!(std::isfinite(aspect) && aspect > 0.0f))
    throw Error("framing needs an aspect ratio > 0, not " + std::to_string(aspect));
  if (!(std::isfinite(preferred_near) && preferred_near > 0.0f))
    throw Error("framing needs a near plane > 0, not " + std::to_string(preferred_near));
  if (bounds.radius < 0.0f) return false;
  const float half_vertical = 0.5f * camera.vertical_fov;
  const float half_horizontal = std::atan(std::tan(half_vertical) * aspect);
  camera.target = bounds.centre;
  camera.distance =
      clamp_distance(bounds.radius / std::sin(std::min(half_vertical, half_horizontal)));
  // No gap where the distance was clamped (a model over about 7.6e13 m across): the preferred near
  // plane then. Half the gap leaves the sphere's front well beyond it.
  const float gap = camera.distance - bounds.radius;
  camera.near_plane = gap > 0.0f ? std::min(preferred_near, 0.5f * gap) : preferred_near;
  return true;
}

bool frame_scene(OrbitCamera& camera, const Scene& scene, float aspect, float preferred_near) {
  return frame_sphere(camera, scene_bounds(scene), aspect, preferred_near);
}

Camera framed_camera(const Scene& scene, float aspect) {
  OrbitCamera orbit = from_camera(Camera{});
  if (!frame_scene(orbit, scene, aspect, Camera{}.near_plane)) return Camera{};
  return to_camera(orbit);
}

}  // namespace tessera
