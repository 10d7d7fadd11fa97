#include "core/bench_scenes.h"

#include <cmath>
#include <random>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/mesh.h"

namespace tessera {
namespace {

constexpr BenchFamilyInfo kFamilies[] = {
    {"grid", "N spheres on a grid filling the view (triangles shrink as N grows)"},
    {"scatter", "N small spheres scattered in depth (heavy overdraw)"},
    {"huge", "N triangles each many times the screen, stacked in depth"},
};

// A 7 x 7 palette of metallic-roughness materials, as in the default scene.
void add_palette(Scene& s) {
  for (int row = 0; row < 7; ++row) {
    for (int col = 0; col < 7; ++col) {
      s.materials.push_back(
          {glm::vec3(0.5f, 0.1f + 0.1f * (col % 3), 0.05f), row / 6.0f, col / 6.0f});
    }
  }
}

void add_four_lights(Scene& s, float distance) {
  for (glm::vec3 d :
       {glm::vec3(-1, 1, 1), glm::vec3(1, 1, 1), glm::vec3(-1, -1, 1), glm::vec3(1, -1, 1)}) {
    Light l;
    l.position = d * distance;
    l.intensity = 3.0f * distance * distance;  // about the default scene's brightness
    s.lights.push_back(l);
  }
}

}  // namespace

std::span<const BenchFamilyInfo> bench_families() {
  return kFamilies;
}

Scene make_bench_scene(std::string_view family, uint32_t objects, uint32_t segments, float aspect) {
  if (objects == 0) throw Error("a benchmark scene needs at least one object");
  if (segments < 4)
    throw Error("spheres need at least 4 segments (got " + std::to_string(segments) + ")");
  if (!(aspect > 0.0f) || !std::isfinite(aspect)) throw Error("the image aspect must be positive");
  Scene s;
  s.background = {0.02f, 0.02f, 0.025f};
  s.ambient = glm::vec3(0.03f);
  add_palette(s);
  const float tan_half = std::tan(glm::radians(45.0f) / 2.0f);

  if (family == "grid") {
    s.meshes.push_back(make_uv_sphere(segments, segments / 2));
    const uint32_t cols = std::max(1u, uint32_t(std::ceil(std::sqrt(double(objects) * aspect))));
    const uint32_t rows = (objects + cols - 1) / cols;
    const float spacing = 2.5f;
    for (uint32_t i = 0; i < objects; ++i) {
      const float x = (float(i % cols) - (cols - 1) / 2.0f) * spacing;
      const float y = (float(i / cols) - (rows - 1) / 2.0f) * spacing;
      s.objects.push_back(
          {0, (i / cols % 7) * 7 + i % cols % 7, glm::translate(glm::mat4(1.0f), {x, y, 0.0f})});
    }
    // Far enough that the whole grid fits: half extents over tan of the half angles.
    const float half_w = cols * spacing / 2.0f, half_h = rows * spacing / 2.0f;
    const float distance = std::max(half_h / tan_half, half_w / (tan_half * aspect)) + 1.0f;
    s.camera.position = {0.0f, 0.0f, distance};
    s.camera.near_plane = std::max(0.1f, distance * 1e-3f);
    add_four_lights(s, std::max(10.0f, distance * 0.5f));
    return s;
  }
  if (family == "scatter") {
    s.meshes.push_back(make_uv_sphere(segments, segments / 2));
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    // Depths 5 to 50 in front of the camera, spread over the view at each depth.
    for (uint32_t i = 0; i < objects; ++i) {
      const float depth = 5.0f + 45.0f * u(rng);
      const float x = (u(rng) * 2 - 1) * depth * tan_half * aspect * 0.9f;
      const float y = (u(rng) * 2 - 1) * depth * tan_half * 0.9f;
      glm::mat4 t = glm::scale(glm::translate(glm::mat4(1.0f), {x, y, -depth}), glm::vec3(0.6f));
      s.objects.push_back({0, uint32_t(rng() % s.materials.size()), t});
    }
    s.camera.position = {0.0f, 0.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, -1.0f};
    add_four_lights(s, 10.0f);
    return s;
  }
  if (family == "huge") {
    Mesh m;
    m.positions = {{-60.0f, -40.0f, 0.0f}, {60.0f, -40.0f, 0.0f}, {0.0f, 80.0f, 0.0f}};
    m.normals.assign(3, {0.0f, 0.0f, 1.0f});
    m.uvs = {{0, 0}, {1, 0}, {0.5f, 1}};
    m.indices = {0, 1, 2};
    s.meshes.push_back(m);
    for (uint32_t i = 0; i < objects; ++i) {
      // Nearest last, so that each new triangle overdraws the ones before it.
      const float depth = 10.0f + 10.0f * float(objects - 1 - i) / float(objects);
      s.objects.push_back({0, i % uint32_t(s.materials.size()),
                           glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -depth})});
    }
    s.camera.position = {0.0f, 0.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, -1.0f};
    add_four_lights(s, 8.0f);
    return s;
  }
  std::string known;
  for (const auto& f : kFamilies) known += (known.empty() ? "" : ", ") + std::string(f.name);
  throw Error("unknown benchmark scene '" + std::string(family) + "' (known: " + known + ")");
}

}  // namespace tessera
