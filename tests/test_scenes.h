#pragma once
// Scenes for accuracy and stability tests: random scenes from a seed, and one scene for each
// place where rasterizers and BRDFs are known to fail.

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "core/scene.h"

namespace tessera::test {

/// Random meshes (jittered closed spheres, cubes, planes, triangle soups), transforms,
/// materials (including roughness and metallic exactly 0 and 1), lights and camera.
Scene random_scene(uint32_t seed);

/// A closed, non-convex mesh: an icosphere of `level` with each vertex moved radially by a
/// random factor in [1 - bumpiness, 1 + bumpiness].
Mesh bumpy_sphere(uint32_t level, float bumpiness, uint32_t seed);

struct StabilityCase {
  std::string name;
  std::function<Scene()> make;
  uint32_t width = 160;
  uint32_t height = 120;
  CullMode cull = CullMode::back;
};

// Shown in test names and logs instead of the object's bytes.
inline void PrintTo(const StabilityCase& c, std::ostream* os) {
  *os << c.name;
}

/// Every stability case of docs/accuracy.md.
std::vector<StabilityCase> stability_cases();

}  // namespace tessera::test
