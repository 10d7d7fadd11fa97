#include "core/procedural_textures.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.h"

namespace tessera {
namespace {

uint8_t to_unorm(double v) {
  return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

uint8_t to_srgb(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return to_unorm(linear <= 0.0031308 ? 12.92 * linear
                                      : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055);
}

Texture blank(uint32_t size, bool srgb) {
  Texture t;
  t.width = t.height = size;
  t.srgb = srgb;
  t.texels.resize(size_t(size) * size);
  return t;
}

}  // namespace

Texture make_checker_texture(uint32_t size, uint32_t cells, glm::vec3 a, glm::vec3 b) {
  if (size < 1 || cells < 1 || size > kMaxTextureSide) {
    throw Error("a checker texture needs a size from 1 to " + std::to_string(kMaxTextureSide) +
                " and at least one cell");
  }
  Texture t = blank(size, true);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const bool odd = ((uint64_t(x) * cells / size) + (uint64_t(y) * cells / size)) % 2;
      const glm::vec3 c = odd ? b : a;
      t.texels[size_t(y) * size + x] = {to_srgb(c.r), to_srgb(c.g), to_srgb(c.b), 255};
    }
  }
  return t;
}

TileMaps make_tile_maps(uint32_t size, uint32_t tiles, glm::vec3 color, float strength) {
  if (size < 4 || tiles < 1 || size > kMaxTextureSide) {
    throw Error("tile maps need a size from 4 to " + std::to_string(kMaxTextureSide) +
                " and at least one tile");
  }
  // Height over the tile: 1 on the flat top, falling linearly to 0 over the bevel, 0 in the
  // grout. Coordinates in tile units, periodic.
  const double grout = 0.04, bevel = 0.08;
  auto height = [&](double u, double v) {
    auto edge = [&](double t) {
      t -= std::floor(t);
      const double d = std::min(t, 1.0 - t);  // distance to the tile's border
      return std::clamp((d - grout) / bevel, 0.0, 1.0);
    };
    return std::min(edge(u * tiles), edge(v * tiles));
  };
  TileMaps m{blank(size, true), blank(size, false), blank(size, false), blank(size, false)};
  const double step = 1.0 / size;
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const double u = (x + 0.5) * step, v = (y + 0.5) * step;
      const double h = height(u, v);
      const size_t i = size_t(y) * size + x;
      const double shade = 0.35 + 0.65 * h;  // grout darker
      m.base_color.texels[i] = {to_srgb(color.r * shade), to_srgb(color.g * shade),
                                to_srgb(color.b * shade), 255};
      // glTF: G roughness, B metallic (factors multiply these).
      m.metallic_roughness.texels[i] = {0, to_unorm(0.35 + 0.6 * (1.0 - h)), 255, 255};
      m.occlusion.texels[i] = {to_unorm(0.4 + 0.6 * h), 0, 0, 255};
      // Slopes in height per uv unit, scaled to tile units; v grows down the rows, and the
      // tangent frame's bitangent follows +v, so the normal is (-dh/du, -dh/dv, 1).
      const double dhdu = (height(u + step, v) - height(u - step, v)) / (2.0 * step * tiles);
      const double dhdv = (height(u, v + step) - height(u, v - step)) / (2.0 * step * tiles);
      glm::dvec3 n(-dhdu * strength, -dhdv * strength, 1.0);
      n = glm::normalize(n);
      m.normal.texels[i] = {to_unorm(n.x * 0.5 + 0.5), to_unorm(n.y * 0.5 + 0.5),
                            to_unorm(n.z * 0.5 + 0.5), 255};
    }
  }
  return m;
}

}  // namespace tessera
