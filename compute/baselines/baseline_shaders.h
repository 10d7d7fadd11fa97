#pragma once
// Embedded SPIR-V of the baselines' shaders (compute/baselines/shaders/, every file there),
// compiled at build time.

#include <cstdint>
#include <span>
#include <string_view>

namespace tessera {

/// The SPIR-V words of the shader compiled from `compute/baselines/shaders/<file>`, named by
/// the file name with '.' as '_' and without ".comp" (`baseline_shade_vert`, `brdf_probe`).
/// The span points into static storage (valid for the program's life); empty when no shader
/// has that name.
std::span<const uint32_t> find_baseline_shader(std::string_view name);

}  // namespace tessera
