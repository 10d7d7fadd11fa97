#pragma once
// Measured reflectance at normal incidence (F0) of common metals, for metallic materials.

#include <span>
#include <string_view>

#include <glm/glm.hpp>

namespace tessera {

struct MetalPreset {
  std::string_view name;
  glm::vec3 f0;  // linear RGB reflectance at normal incidence: a metal's base colour
};

/// All presets, in a fixed order. The span refers to static storage.
std::span<const MetalPreset> metal_presets();

/// The preset called `name` (lower case, e.g. "gold"), or nullptr if there is none.
const MetalPreset* find_metal_preset(std::string_view name);

}  // namespace tessera
