#include "tests/test_scenes.h"

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/mesh.h"

namespace tessera::test {
namespace {

Mesh triangle_soup(std::mt19937& rng, int count) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Mesh m;
  for (int t = 0; t < count; ++t) {
    glm::vec3 p[3] = {{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    n = glm::length(n) > 1e-6f ? glm::normalize(n) : glm::vec3(0, 0, 1);
    for (int k = 0; k < 3; ++k) {
      m.positions.push_back(p[k]);
      m.normals.push_back(n);
      m.uvs.push_back({k == 1, k == 2});
      m.indices.push_back(uint32_t(m.positions.size() - 1));
    }
  }
  return m;
}

// Camera at the origin looking down -z with the given near plane; one white point light.
Scene bare_scene(float near_plane = 0.1f) {
  Scene s;
  s.camera.position = {0, 0, 0};
  s.camera.target = {0, 0, -1};
  s.camera.vertical_fov = glm::radians(60.0f);
  s.camera.near_plane = near_plane;
  s.background = {0.1f, 0.2f, 0.3f};
  s.ambient = {0.02f, 0.02f, 0.02f};
  s.materials.push_back({glm::vec3(0.7f, 0.6f, 0.5f), 0.0f, 0.5f});
  Light light;
  light.position = {1.0f, 2.0f, 1.0f};
  light.intensity = 20.0f;
  s.lights.push_back(light);
  return s;
}

// A mesh of explicit triangles with flat normals (zero normals where a triangle is degenerate).
Mesh triangles(const std::vector<glm::vec3>& corners) {
  Mesh m;
  for (size_t i = 0; i + 2 < corners.size(); i += 3) {
    glm::vec3 n = glm::cross(corners[i + 1] - corners[i], corners[i + 2] - corners[i]);
    n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1);
    for (int k = 0; k < 3; ++k) {
      m.positions.push_back(corners[i + k]);
      m.normals.push_back(n);
      m.uvs.push_back({k == 1, k == 2});
      m.indices.push_back(uint32_t(m.positions.size() - 1));
    }
  }
  return m;
}

Scene with_mesh(Scene s, Mesh m, glm::mat4 transform = glm::mat4(1.0f)) {
  s.meshes.push_back(std::move(m));
  s.objects.push_back({uint32_t(s.meshes.size() - 1), 0, transform});
  return s;
}

}  // namespace

Mesh bumpy_sphere(uint32_t level, float bumpiness, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(1.0f - bumpiness, 1.0f + bumpiness);
  Mesh m = make_icosphere(level);
  for (glm::vec3& p : m.positions) p *= u(rng);
  m.analytic_sphere.reset();  // no longer a sphere
  return m;
}

Scene random_scene(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto range = [&](float a, float b) { return a + (b - a) * u(rng); };
  Scene s;
  s.meshes.push_back(bumpy_sphere(2, 0.15f, seed));
  s.meshes.push_back(make_cube());
  s.meshes.push_back(make_plane(3, 2));
  s.meshes.push_back(make_uv_sphere(12 + seed % 8, 6 + seed % 5));
  s.meshes.push_back(triangle_soup(rng, 12));
  for (int i = 0; i < 6; ++i) {
    Material m;
    m.base_color = {u(rng), u(rng), u(rng)};
    const float extremes[] = {0.0f, 1.0f, range(0.0f, 1.0f)};
    m.metallic = extremes[i % 3];
    m.roughness = extremes[(i / 3 + i) % 3];
    s.materials.push_back(m);
  }
  const int objects = 6 + int(seed % 10);
  for (int i = 0; i < objects; ++i) {
    glm::mat4 t = glm::translate(glm::mat4(1.0f), {range(-3, 3), range(-2, 2), range(-3, 3)});
    t = glm::rotate(t, range(0, 6.28f),
                    glm::normalize(glm::vec3(range(-1, 1), range(-1, 1), range(0.1f, 1))));
    t = glm::scale(t, {range(0.3f, 1.5f), range(0.3f, 1.5f), range(0.3f, 1.5f)});
    s.objects.push_back(
        {uint32_t(rng() % s.meshes.size()), uint32_t(rng() % s.materials.size()), t});
  }
  const int lights = 1 + int(seed % 4);
  for (int i = 0; i < lights; ++i) {
    Light l;
    l.kind = i % 3 == 2 ? LightKind::directional : LightKind::point;
    l.position = {range(-6, 6), range(-6, 6), range(-6, 6)};
    l.direction = glm::normalize(glm::vec3(range(-1, 1), range(-1, -0.2f), range(-1, 1)));
    l.color = {range(0.5f, 1), range(0.5f, 1), range(0.5f, 1)};
    l.intensity = l.kind == LightKind::point ? range(10, 80) : range(0.5f, 3);
    s.lights.push_back(l);
  }
  const float yaw = range(0, 6.28f), pitch = range(-0.6f, 0.6f), distance = range(6, 10);
  s.camera.position = distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                           std::cos(pitch) * std::cos(yaw));
  s.camera.vertical_fov = glm::radians(range(30, 70));
  s.camera.near_plane = range(0.05f, 0.5f);
  s.background = {u(rng) * 0.2f, u(rng) * 0.2f, u(rng) * 0.2f};
  s.ambient = glm::vec3(range(0, 0.1f));
  return s;
}

std::vector<StabilityCase> stability_cases() {
  std::vector<StabilityCase> cases;
  cases.push_back(
      {"roughness_and_metallic_extremes", [] { return make_sphere_grid_scene(); }, 256, 256});
  cases.push_back({"grazing_plane_and_silhouettes", [] {
                     Scene s = bare_scene();
                     s.materials[0].roughness = 0.0f;
                     s = with_mesh(s, make_uv_sphere(32, 16),
                                   glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -4.0f}));
                     // A plane containing the view axis: N.V = 0 along it.
                     glm::mat4 edge_on = glm::translate(glm::mat4(1.0f), {1.2f, 0.0f, -4.0f});
                     edge_on = glm::rotate(edge_on, glm::radians(90.0f), {0, 1, 0});
                     s = with_mesh(s, make_plane(4, 4), edge_on);
                     // And one tilted a hair away from edge-on.
                     glm::mat4 nearly = glm::translate(glm::mat4(1.0f), {-1.5f, 0.0f, -4.0f});
                     nearly = glm::rotate(nearly, glm::radians(89.9f), {0, 1, 0});
                     return with_mesh(s, make_plane(4, 4), nearly);
                   }});
  cases.push_back({"light_on_and_behind_the_surface", [] {
                     Scene s = bare_scene();
                     s.lights.clear();
                     Light on;
                     on.position = {0.0f, 0.0f, -3.0f};  // the sphere's front pole, a vertex
                     on.intensity = 5.0f;
                     Light behind;
                     behind.position = {0.0f, 0.0f, -6.0f};
                     behind.intensity = 50.0f;
                     s.lights = {on, behind};
                     for (float r : {0.0f, 1.0f}) s.materials.push_back({glm::vec3(0.9f), 1.0f, r});
                     s = with_mesh(s, make_uv_sphere(32, 16),
                                   glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -4.0f}));
                     s.objects.back().material = 1;
                     return s;
                   }});
  cases.push_back({"zero_intensity_lights", [] {
                     Scene s = bare_scene();
                     s.lights[0].intensity = 0.0f;
                     Light sun;
                     sun.kind = LightKind::directional;
                     sun.intensity = 0.0f;
                     s.lights.push_back(sun);
                     return with_mesh(s, make_icosphere(3),
                                      glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -4.0f}));
                   }});
  cases.push_back({"no_lights", [] {
                     Scene s = bare_scene();
                     s.lights.clear();
                     return with_mesh(s, make_icosphere(3),
                                      glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -4.0f}));
                   }});
  cases.push_back({"near_plane_crossing_and_behind_camera",
                   [] {
                     Scene s = bare_scene(0.5f);
                     s = with_mesh(s, triangles({{-2.0f, -1.5f, -4.0f},
                                                 {2.5f, -1.0f, -3.0f},
                                                 {0.3f, 0.8f, 1.5f},
                                                 {-1.0f, -1.0f, 2.0f},
                                                 {1.0f, -1.0f, 2.0f},
                                                 {0.0f, 1.0f, 0.3f},
                                                 {-0.4f, 0.3f, -2.0f},
                                                 {-1.0f, 3.0f, -0.3f},
                                                 {3.0f, 2.0f, 0.2f}}));
                     return s;
                   },
                   160, 120, CullMode::none});
  cases.push_back({"degenerate_triangles", [] {
                     Scene s = bare_scene();
                     const glm::vec3 a(-1, -1, -4), b(1, -1, -4), c(0, 1, -4);
                     return with_mesh(s, triangles({a, a, a,               // one point
                                                    a, b, (a + b) * 0.5f,  // collinear
                                                    a, a, c,               // duplicate vertex
                                                    a, c, b,               // back face
                                                    a, b, c}));            // a real one
                   }});
  cases.push_back({"huge_triangle", [] {
                     Scene s = bare_scene();
                     // Hundreds of times the screen in each direction, then one on screen.
                     return with_mesh(s, triangles({{-3000, -2000, -5},
                                                    {3000, -2000, -5},
                                                    {0, 4000, -5},
                                                    {-0.5f, -0.5f, -3},
                                                    {0.5f, -0.5f, -3},
                                                    {0.0f, 0.5f, -3}}));
                   }});
  cases.push_back(
      {"subpixel_triangles", [] {
         Scene s = bare_scene();
         std::vector<glm::vec3> corners;
         std::mt19937 rng(5);
         std::uniform_real_distribution<float> u(-1.0f, 1.0f);
         for (int i = 0; i < 4000; ++i) {
           glm::vec3 p(u(rng) * 2.5f, u(rng) * 1.8f, -4.0f);
           const float e = 0.004f;  // a tenth of a pixel
           corners.insert(corners.end(), {p, p + glm::vec3(e, 0, 0), p + glm::vec3(0, e, 0)});
         }
         return with_mesh(s, triangles(corners));
       }});
  cases.push_back(
      {"million_triangles_in_one_tile", [] {
         Scene s = bare_scene();
         // A 256-triangle fan around the centre of tile (4, 3), instanced 4096 times at
         // depths a hair apart: 1,048,576 triangles within one 16x16 tile.
         std::vector<glm::vec3> corners;
         const float cx = (4 * 16 + 8 + 0.5f - 80.0f) / 60.0f * 0.57735f * 4.0f;
         const float cy = -(3 * 16 + 8 + 0.5f - 60.0f) / 60.0f * 0.57735f * 4.0f;
         for (int k = 0; k < 256; ++k) {
           const float a0 = k * 6.2831853f / 256, a1 = (k + 1) * 6.2831853f / 256;
           const float r = 0.2f;
           corners.insert(corners.end(), {{cx, cy, -4.0f},
                                          {cx + r * std::cos(a0), cy + r * std::sin(a0), -4.0f},
                                          {cx + r * std::cos(a1), cy + r * std::sin(a1), -4.0f}});
         }
         s.meshes.push_back(triangles(corners));
         for (int i = 0; i < 4096; ++i) {
           s.objects.push_back({0, 0, glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -0.0001f * i})});
         }
         return s;
       }});
  // A planet: a sphere of radius 10^6 m seen from 3 * 10^6 m with the default 0.1 m near
  // plane. Camera rays built as a far-plane point minus the camera's position lost their
  // direction to float rounding there (0.25 m steps on a 100 m far plane), and the compute
  // path shaded every facet (68 levels off the reference).
  cases.push_back({"far_from_the_origin_with_a_near_plane_of_0_1_m",
                   [] {
                     Scene s = bare_scene();
                     s.camera.position = {0.0f, 0.0f, 3e6f};
                     s.camera.target = {0.0f, 0.0f, 0.0f};
                     s.lights.clear();
                     Light sun;
                     sun.kind = LightKind::directional;
                     sun.direction = glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f));
                     sun.intensity = 3.0f;
                     s.lights.push_back(sun);
                     return with_mesh(s, make_uv_sphere(64, 32),
                                      glm::scale(glm::mat4(1.0f), glm::vec3(1e6f)));
                   },
                   96, 96});
  cases.push_back({"triangles_on_tile_boundaries", [] {
                     Scene s = bare_scene();
                     // Camera so that world x = px / 40 - 2, y = 1.5 - py / 40 on the plane z = -2.
                     s.camera.vertical_fov = 2.0f * std::atan(1.5f / 2.0f);
                     std::vector<glm::vec3> corners;
                     auto world = [](float px, float py) {
                       return glm::vec3(px / 40.0f - 2.0f, 1.5f - py / 40.0f, -2.0f);
                     };
                     for (int ty = 0; ty < 7; ++ty) {
                       for (int tx = 0; tx < 9; ++tx) {
                         // Vertices exactly on tile corners (multiples of 16 px).
                         glm::vec3 a = world(tx * 16.0f, ty * 16.0f),
                                   b = world(tx * 16.0f + 16, ty * 16.0f);
                         glm::vec3 c = world(tx * 16.0f, ty * 16.0f + 16),
                                   d = world(tx * 16.0f + 16, ty * 16.0f + 16);
                         corners.insert(corners.end(), {a, c, b, b, c, d});
                       }
                     }
                     return with_mesh(s, triangles(corners));
                   }});
  return cases;
}

}  // namespace tessera::test
