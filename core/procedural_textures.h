#pragma once
// Texture maps made in code, for the built-in scenes and the tests (no files needed).

#include <cstdint>

#include <glm/glm.hpp>

#include "core/texture.h"

namespace tessera {

/// A `size` x `size` sRGB checkerboard of `cells` x `cells` squares of colours a and b
/// (linear RGB, encoded to sRGB). Requires size >= 1 and cells >= 1 (throws Error).
Texture make_checker_texture(uint32_t size, uint32_t cells, glm::vec3 a, glm::vec3 b);

/// Tiles with bevelled edges, `tiles` x `tiles` over the texture, as four glTF-style maps
/// of `size` x `size` texels: base colour (sRGB, tiles in `color` with darker grout),
/// metallic-roughness (grout rougher), tangent-space normal (from the bevels' height field
/// by central differences; `strength` scales the slopes), occlusion (grout darker).
struct TileMaps {
  Texture base_color, metallic_roughness, normal, occlusion;
};
TileMaps make_tile_maps(uint32_t size, uint32_t tiles, glm::vec3 color, float strength);

}  // namespace tessera
