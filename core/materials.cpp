#include "core/materials.h"

namespace tessera {
namespace {

// Linear-RGB F0 of metals as tabulated in Google's Filament documentation ("Physically Based
// Rendering in Filament", section 4.8.3.2, table "f0 for common metals"), which derives them
// from measured spectral indices of refraction (refractiveindex.info) as in Hoffman 2015,
// "Physics and Math of Shading", SIGGRAPH course notes.
constexpr MetalPreset kPresets[] = {
    {"silver", {0.97f, 0.96f, 0.91f}},   {"aluminium", {0.91f, 0.92f, 0.92f}},
    {"titanium", {0.76f, 0.73f, 0.69f}}, {"iron", {0.77f, 0.78f, 0.78f}},
    {"platinum", {0.83f, 0.81f, 0.78f}}, {"gold", {1.00f, 0.85f, 0.57f}},
    {"brass", {0.98f, 0.90f, 0.59f}},    {"copper", {0.97f, 0.74f, 0.62f}},
};

}  // namespace

std::span<const MetalPreset> metal_presets() {
  return kPresets;
}

const MetalPreset* find_metal_preset(std::string_view name) {
  for (const MetalPreset& p : kPresets) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

}  // namespace tessera
