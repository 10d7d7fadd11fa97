#include "core/materials.h"

#include <array>
#include <cmath>
#include <iterator>

namespace tessera {
namespace {

// F0 of metals as tabulated in Google's Filament documentation ("Physically Based Rendering in
// Filament", section 4.8.3.2, table "f0 for common metals"), which derives them from measured
// spectral indices of refraction as in Hoffman 2015, "Physics and Math of Shading", SIGGRAPH
// course notes. The table's numbers are sRGB-encoded (its titanium 0.76, 0.73, 0.69 is the
// sRGB encoding of Hoffman's linear 0.542, 0.497, 0.449), while a base colour is linear RGB:
// used as they stand, every metal rendered too pale (gold nearly cream). So they are kept as
// published here and decoded below.
struct PublishedMetal {
  std::string_view name;
  glm::vec3 f0_srgb;
};
constexpr PublishedMetal kPublished[] = {
    {"silver", {0.97f, 0.96f, 0.91f}},   {"aluminium", {0.91f, 0.92f, 0.92f}},
    {"titanium", {0.76f, 0.73f, 0.69f}}, {"iron", {0.77f, 0.78f, 0.78f}},
    {"platinum", {0.83f, 0.81f, 0.78f}}, {"gold", {1.00f, 0.85f, 0.57f}},
    {"brass", {0.98f, 0.90f, 0.59f}},    {"copper", {0.97f, 0.74f, 0.62f}},
};
constexpr size_t kPresetCount = std::size(kPublished);

// The sRGB electro-optical transfer function (IEC 61966-2-1), in double for exact rounding.
float srgb_decode(float encoded) {
  const double c = encoded;
  return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

const std::array<MetalPreset, kPresetCount>& presets() {
  static const std::array<MetalPreset, kPresetCount> table = [] {
    std::array<MetalPreset, kPresetCount> t{};
    for (size_t i = 0; i < kPresetCount; ++i) {
      const glm::vec3 e = kPublished[i].f0_srgb;
      t[i] = {kPublished[i].name, {srgb_decode(e.r), srgb_decode(e.g), srgb_decode(e.b)}};
    }
    return t;
  }();
  return table;
}

}  // namespace

std::span<const MetalPreset> metal_presets() {
  return presets();
}

const MetalPreset* find_metal_preset(std::string_view name) {
  for (const MetalPreset& p : presets()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

}  // namespace tessera
