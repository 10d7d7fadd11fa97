#pragma once
// Scenes built into Tessera, by name.

#include <span>
#include <string_view>

#include "core/scene.h"

namespace tessera {

struct BuiltinSceneInfo {
  std::string_view name;
  std::string_view description;
};

/// Names and one-line descriptions of the built-in scenes; the first is the default.
std::span<const BuiltinSceneInfo> builtin_scenes();

/// True if `name` is a built-in scene.
bool is_builtin_scene(std::string_view name);

/// Builds the built-in scene `name`. Throws Error naming the known scenes if there is none.
Scene make_builtin_scene(std::string_view name);

/// The classic PBR demo: a 7 x 7 grid of spheres, metallic rising from 0 (bottom row) to 1
/// (top row) and roughness from exactly 0 (left column) to exactly 1 (right), lit by four
/// point lights. Sphere (row, column) is object row * 7 + column.
Scene make_sphere_grid_scene();

/// A row of metal presets (columns) at three roughness values (rows), two point lights and a
/// directional light.
Scene make_metals_scene();

/// Each kind of light: a soft spot, a hard-edged spot (equal inner and outer angles), a point
/// light with inverse-square falloff and a range, a point light with classic attenuation and
/// a directional light, over three spheres on a floor.
Scene make_lights_scene();

/// Texture maps: a far-reaching checkered floor (mip-mapping and anisotropic filtering show at
/// its horizon) and three spheres: tiles with all four maps (base colour, metallic-roughness,
/// normal, occlusion) on a dielectric and on gold, and a checkered copper.
Scene make_textured_scene();

/// Image-based lighting: two rows of five spheres (gold above, white dielectric below),
/// roughness 0 to 1 left to right, lit only by a procedural sky (make_sky_environment).
Scene make_environment_scene();

}  // namespace tessera
