#pragma once
// GoogleTest assertions on scenes (core/scene.h).

#include "core/scene.h"

namespace tessera {

/// Every field of two scenes, floats compared exactly, each difference reported with the
/// array element it is in (meshes, materials, objects, lights, textures, environment texels).
void expect_same_scene(const Scene& a, const Scene& b);

}  // namespace tessera
