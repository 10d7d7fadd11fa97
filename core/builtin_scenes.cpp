#include "core/builtin_scenes.h"

#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/materials.h"
#include "core/mesh.h"

namespace tessera {
namespace {

constexpr BuiltinSceneInfo kScenes[] = {
    {"spheres", "7x7 spheres, metallic by row and roughness by column, four point lights"},
    {"metals", "metal presets (gold, copper, ...) at three roughness values"},
};

glm::mat4 place(glm::vec3 position, float scale) {
  return glm::scale(glm::translate(glm::mat4(1.0f), position), glm::vec3(scale));
}

}  // namespace

std::span<const BuiltinSceneInfo> builtin_scenes() {
  return kScenes;
}

bool is_builtin_scene(std::string_view name) {
  for (const auto& s : kScenes) {
    if (s.name == name) return true;
  }
  return false;
}

Scene make_builtin_scene(std::string_view name) {
  if (name == "spheres") return make_sphere_grid_scene();
  if (name == "metals") return make_metals_scene();
  std::string known;
  for (const auto& s : kScenes) known += (known.empty() ? "" : ", ") + std::string(s.name);
  throw Error("unknown scene '" + std::string(name) + "' (known scenes: " + known + ")");
}

Scene make_sphere_grid_scene() {
  Scene scene;
  scene.camera.position = {0.0f, 0.0f, 22.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.vertical_fov = glm::radians(45.0f);
  scene.camera.near_plane = 0.1f;
  scene.background = {0.02f, 0.02f, 0.025f};
  scene.ambient = {0.03f, 0.03f, 0.03f};
  scene.meshes.push_back(make_uv_sphere(64, 32));

  constexpr int kGrid = 7;
  constexpr float kSpacing = 2.5f;
  for (int row = 0; row < kGrid; ++row) {
    for (int col = 0; col < kGrid; ++col) {
      Material m;
      m.base_color = {0.5f, 0.0f, 0.0f};
      m.metallic = float(row) / float(kGrid - 1);
      m.roughness = float(col) / float(kGrid - 1);
      scene.materials.push_back(m);
      Object o;
      o.mesh = 0;
      o.material = uint32_t(scene.materials.size() - 1);
      o.transform = place(
          {(col - (kGrid - 1) / 2.0f) * kSpacing, (row - (kGrid - 1) / 2.0f) * kSpacing, 0.0f},
          1.0f);
      scene.objects.push_back(o);
    }
  }
  for (glm::vec3 p : {glm::vec3(-10, 10, 10), glm::vec3(10, 10, 10), glm::vec3(-10, -10, 10),
                      glm::vec3(10, -10, 10)}) {
    Light light;
    light.kind = LightKind::point;
    light.position = p;
    light.color = glm::vec3(1.0f);
    light.intensity = 300.0f;
    scene.lights.push_back(light);
  }
  return scene;
}

Scene make_metals_scene() {
  Scene scene;
  const auto presets = metal_presets();
  const float columns = float(presets.size());
  scene.camera.position = {0.0f, 0.0f, 2.6f * columns};
  scene.camera.vertical_fov = glm::radians(30.0f);
  scene.background = {0.03f, 0.03f, 0.035f};
  scene.ambient = {0.08f, 0.08f, 0.08f};
  scene.meshes.push_back(make_uv_sphere(64, 32));
  const float roughness[] = {0.15f, 0.4f, 0.75f};
  for (int row = 0; row < 3; ++row) {
    for (size_t col = 0; col < presets.size(); ++col) {
      Material m;
      m.base_color = presets[col].f0;
      m.metallic = 1.0f;
      m.roughness = roughness[row];
      scene.materials.push_back(m);
      Object o;
      o.material = uint32_t(scene.materials.size() - 1);
      o.transform =
          place({(float(col) - (columns - 1) / 2.0f) * 2.2f, (1 - row) * 2.2f, 0.0f}, 1.0f);
      scene.objects.push_back(o);
    }
  }
  Light key;
  key.position = {-6.0f, 6.0f, 10.0f};
  key.intensity = 250.0f;
  Light fill;
  fill.position = {8.0f, -2.0f, 8.0f};
  fill.color = {0.8f, 0.85f, 1.0f};
  fill.intensity = 120.0f;
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.6f));
  sun.intensity = 2.0f;
  scene.lights = {key, fill, sun};
  return scene;
}

}  // namespace tessera
