#include "core/builtin_scenes.h"

#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/materials.h"
#include "core/mesh.h"
#include "core/procedural_textures.h"

namespace tessera {
namespace {

constexpr BuiltinSceneInfo kScenes[] = {
    {"spheres", "7x7 spheres, metallic by row and roughness by column, four point lights"},
    {"metals", "metal presets (gold, copper, ...) at three roughness values"},
    {"lights", "spot, point (both falloffs) and directional lights over spheres and a floor"},
    {"textured", "texture maps: a checkered floor to the horizon, tiled spheres with normal maps"},
    {"environment", "spheres by roughness, metal and dielectric, lit by a procedural sky"},
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
  if (name == "lights") return make_lights_scene();
  if (name == "textured") return make_textured_scene();
  if (name == "environment") return make_environment_scene();
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

Scene make_lights_scene() {
  Scene scene;
  scene.camera.position = {0.0f, 4.0f, 11.0f};
  scene.camera.target = {0.0f, 0.5f, 0.0f};
  scene.camera.vertical_fov = glm::radians(40.0f);
  scene.background = {0.01f, 0.01f, 0.015f};
  scene.ambient = glm::vec3(0.01f);
  scene.meshes.push_back(make_uv_sphere(48, 24));
  scene.meshes.push_back(make_plane(16, 16));
  scene.materials.push_back({glm::vec3(0.6f), 0.0f, 0.8f});  // floor
  scene.materials.push_back({glm::vec3(0.8f, 0.2f, 0.1f), 0.0f, 0.3f});
  scene.materials.push_back({glm::vec3(0.95f, 0.64f, 0.54f), 1.0f, 0.25f});  // copper-like
  scene.materials.push_back({glm::vec3(0.2f, 0.5f, 0.9f), 0.0f, 0.6f});
  glm::mat4 floor = glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0));
  scene.objects.push_back({1, 0, glm::scale(floor, glm::vec3(8.0f))});
  for (int i = 0; i < 3; ++i) {
    scene.objects.push_back({0, uint32_t(1 + i), place({(i - 1) * 3.0f, 1.0f, 0.0f}, 1.0f)});
  }
  Light spot;  // a soft-edged spot from above the left sphere
  spot.kind = LightKind::spot;
  spot.position = {-3.0f, 6.0f, 2.0f};
  spot.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -0.3f));
  spot.inner_angle = glm::radians(15.0f);
  spot.outer_angle = glm::radians(25.0f);
  spot.intensity = 120.0f;
  Light hard_spot = spot;  // equal angles: a hard edge
  hard_spot.position = {3.0f, 6.0f, 2.0f};
  hard_spot.inner_angle = hard_spot.outer_angle = glm::radians(18.0f);
  hard_spot.color = {0.6f, 0.8f, 1.0f};
  Light windowed;  // inverse square, fading to zero at 6 m
  windowed.position = {0.0f, 2.5f, 3.0f};
  windowed.range = 6.0f;
  windowed.intensity = 15.0f;
  windowed.color = {1.0f, 0.8f, 0.6f};
  Light classic;  // constant, linear, quadratic attenuation
  classic.falloff = Falloff::classic;
  classic.position = {0.0f, 1.0f, -3.0f};
  classic.attenuation = {1.0f, 0.35f, 0.44f};
  classic.intensity = 8.0f;
  Light moon;
  moon.kind = LightKind::directional;
  moon.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.5f));
  moon.intensity = 0.3f;
  moon.color = {0.7f, 0.75f, 1.0f};
  scene.lights = {spot, hard_spot, windowed, classic, moon};
  return scene;
}

Scene make_textured_scene() {
  Scene scene;
  scene.camera.position = {0.0f, 1.6f, 7.0f};
  scene.camera.target = {0.0f, 0.9f, 0.0f};
  scene.camera.vertical_fov = glm::radians(45.0f);
  scene.background = {0.3f, 0.4f, 0.55f};
  scene.ambient = glm::vec3(0.08f);
  scene.meshes.push_back(make_plane(4, 4));
  scene.meshes.push_back(make_uv_sphere(64, 32));
  // 0: fine checkerboard for the floor (aliases at the horizon without mip-mapping).
  scene.textures.push_back(make_checker_texture(1024, 64, glm::vec3(0.8f), glm::vec3(0.05f)));
  TileMaps tiles = make_tile_maps(512, 8, glm::vec3(0.75f, 0.45f, 0.3f), 1.5f);
  scene.textures.push_back(std::move(tiles.base_color));                                     // 1
  scene.textures.push_back(std::move(tiles.metallic_roughness));                             // 2
  scene.textures.push_back(std::move(tiles.normal));                                         // 3
  scene.textures.push_back(std::move(tiles.occlusion));                                      // 4
  scene.textures.push_back(make_checker_texture(256, 8, glm::vec3(1.0f), glm::vec3(0.3f)));  // 5

  Material floor{glm::vec3(1.0f), 0.0f, 0.7f};
  floor.base_color_map = 0;
  Material tiled{glm::vec3(1.0f), 0.0f, 1.0f};
  tiled.base_color_map = 1;
  tiled.metallic_roughness_map = 2;
  tiled.normal_map = 3;
  tiled.occlusion_map = 4;
  Material tiled_metal = tiled;  // the same maps on gold: metallic from the map's blue
  tiled_metal.base_color = {1.0f, 0.78f, 0.34f};
  tiled_metal.base_color_map = kNoTexture;
  tiled_metal.metallic = 1.0f;
  Material checker_metal{glm::vec3(0.95f, 0.64f, 0.54f), 1.0f, 0.3f};
  checker_metal.base_color_map = 5;
  scene.materials = {floor, tiled, tiled_metal, checker_metal};

  const glm::mat4 floor_xf = glm::scale(
      glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0)), glm::vec3(40.0f));
  scene.objects.push_back({0, 0, floor_xf});
  scene.objects.push_back({1, 1, place({-2.2f, 1.0f, 0.0f}, 1.0f)});
  scene.objects.push_back({1, 2, place({0.0f, 1.0f, -0.5f}, 1.0f)});
  scene.objects.push_back({1, 3, place({2.2f, 1.0f, 0.0f}, 1.0f)});
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = glm::normalize(glm::vec3(-0.5f, -0.8f, -0.6f));
  sun.intensity = 2.5f;
  Light lamp;
  lamp.position = {1.5f, 3.0f, 3.0f};
  lamp.intensity = 12.0f;
  lamp.color = {1.0f, 0.85f, 0.7f};
  scene.lights = {sun, lamp};
  return scene;
}

Scene make_environment_scene() {
  Scene scene;
  scene.camera.position = {0.0f, 0.0f, 15.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.vertical_fov = glm::radians(40.0f);
  scene.environment = std::make_shared<const Environment>(make_sky_environment(1024));
  scene.meshes.push_back(make_uv_sphere(64, 32));
  constexpr int kColumns = 5;
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < kColumns; ++col) {
      Material m;
      m.roughness = float(col) / (kColumns - 1);
      m.metallic = row == 0 ? 1.0f : 0.0f;
      m.base_color = row == 0 ? glm::vec3(1.0f, 0.78f, 0.34f) : glm::vec3(0.9f);  // gold, white
      scene.materials.push_back(m);
      scene.objects.push_back({0, uint32_t(scene.materials.size() - 1),
                               place({(col - 2) * 2.3f, row == 0 ? 1.2f : -1.2f, 0.0f}, 1.0f)});
    }
  }
  return scene;
}

}  // namespace tessera
